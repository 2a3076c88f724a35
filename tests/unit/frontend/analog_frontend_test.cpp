#include <gtest/gtest.h>

#include <cmath>

#include "drivers/frontend/analog_frontend.h"

namespace xr::frontend {
namespace {

TEST(AnalogFrontEnd, DividerScalesBatteryVoltage) {
  AnalogFrontEndSettings s;
  // 1 MΩ / 75 kΩ: 14.4 V -> 14.4 * 75 / 1075 = 1.00465 V at the ADC.
  EXPECT_NEAR(adcFromBatteryVolts(s, 14.4), 14.4 * 75.0 / 1075.0, 1e-12);
  EXPECT_NEAR(batteryVoltsFromAdc(s, adcFromBatteryVolts(s, 13.1)), 13.1, 1e-12);
}

TEST(AnalogFrontEnd, HallZeroAndInvert) {
  AnalogFrontEndSettings s;
  EXPECT_DOUBLE_EQ(altAmpsFromAdc(s, s.hall_zero_v), 0.0);
  EXPECT_NEAR(altAmpsFromAdc(s, 2.5 + 0.02 * 40), 40.0, 1e-9);
  s.hall_invert = true;
  EXPECT_NEAR(altAmpsFromAdc(s, 2.5 + 0.02 * 40), -40.0, 1e-9);
  EXPECT_NEAR(altAmpsFromAdc(s, adcFromAltAmps(s, 55.0)), 55.0, 1e-9);
}

TEST(AnalogFrontEnd, RpmFloorReportsZero) {
  AnalogFrontEndSettings s;
  EXPECT_DOUBLE_EQ(rpmFromAdc(s, 0.01), 0.0);  // 10 RPM is under the 50 RPM floor
  EXPECT_NEAR(rpmFromAdc(s, adcFromRpm(s, 1800.0)), 1800.0, 1e-9);
  s.pulley_ratio = 2.0;
  EXPECT_NEAR(rpmFromAdc(s, 1.0), 500.0, 1e-9);
}

TEST(AnalogFrontEnd, ThermistorRoundTripAndOpenCircuit) {
  AnalogFrontEndSettings s;
  // At T0 the thermistor equals R0 = series R: half the supply.
  EXPECT_NEAR(adcFromTempF(s, 77.0), s.thermistor_supply_v / 2.0, 1e-9);
  EXPECT_NEAR(tempFFromAdc(s, adcFromTempF(s, 180.0)), 180.0, 1e-6);
  EXPECT_TRUE(std::isnan(tempFFromAdc(s, s.thermistor_supply_v)));  // open thermistor
  EXPECT_TRUE(std::isnan(tempFFromAdc(s, 0.0)));                    // shorted thermistor
}

}  // namespace
}  // namespace xr::frontend
