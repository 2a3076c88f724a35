// SimWorld: wiring of the plant to the chips, faults, ALERT cutting the field.
#include <gtest/gtest.h>

#include <cerrno>

#include "drivers/frontend/analog_frontend.h"
#include "drivers/sim/ina228_model.h"
#include "drivers/sim/sim_clock.h"
#include "drivers/sim/sim_world.h"

namespace xr::sim {
namespace {

WorldConfig quiet() {
  WorldConfig c;
  c.noise = NoiseConfig{0, 0, 0, 0, 0, 0};
  return c;
}

std::uint64_t readReg(SimWorld& w, std::uint16_t addr, std::uint8_t reg, int n, int* rc = nullptr) {
  std::uint8_t p = reg, buf[8] = {};
  I2cMsg m[2] = {{addr, false, &p, 1}, {addr, true, buf, std::size_t(n)}};
  const int r = w.i2c().transfer(m);
  if (rc) *rc = r;
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | buf[i];
  return v;
}
int writeReg(SimWorld& w, std::uint16_t addr, std::uint8_t reg, std::uint16_t v) {
  std::uint8_t b[3] = {reg, std::uint8_t(v >> 8), std::uint8_t(v)};
  I2cMsg m{addr, false, b, 3};
  return w.i2c().transfer({&m, 1});
}

TEST(SimWorld, InaSeesBatteryVoltageOnVbus) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  w.advanceTo(fromMs(10));
  const double vbus = double(readReg(w, hw.ina228_address, ina228::VBUS, 3) >> 4) * 195.3125e-6;
  EXPECT_NEAR(vbus, w.truth().plant.battery_v, 0.001);
}

TEST(SimWorld, FieldFollowsPwmAndEnable) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  w.simPwm().setEnabled(true);
  w.simPwm().setDutyPercent(50);
  w.advanceTo(fromSec(1));
  EXPECT_EQ(w.truth().plant.field, 0.0);  // enable still low
  w.fieldEnable().set(true);
  w.advanceTo(fromSec(2));
  EXPECT_NEAR(w.truth().plant.field, 0.5, 0.01);
  EXPECT_TRUE(w.truth().field_on);
  EXPECT_GT(w.truth().plant.alt_a, 10.0);
  ASSERT_GE(w.simFieldEnable().log().changes().size(), 1u);
  EXPECT_EQ(w.simFieldEnable().log().changes().back().t, fromSec(1));
}

TEST(SimWorld, InaAlertOnBovlCutsTheFieldInHardware) {
  HardwareSettings hw;
  WorldConfig c = quiet();
  c.plant.battery.soc_pct = 98.0;  // near the knee: voltage rises fast under charge
  SimWorld w(c, hw);
  writeReg(w, hw.ina228_address, ina228::ADC_CONFIG, (0x9 << 12) | (2 << 9));  // bus only, 150 us
  writeReg(w, hw.ina228_address, ina228::BOVL, std::uint16_t(13.75 / 3.125e-3));
  w.simPwm().setEnabled(true);
  w.simPwm().setDutyPercent(100);
  w.fieldEnable().set(true);
  double peak = 0;
  for (int i = 1; i <= 4000; ++i) {
    w.advanceTo(fromMs(5 * i));
    peak = std::max(peak, w.truth().plant.battery_v);
  }
  // No software acted: the ALERT pin kept the bus near BOVL.
  EXPECT_LT(peak, 13.75 + 0.1);
  EXPECT_GT(peak, 13.7);
  EXPECT_GT(w.ina().conversions(), 0u);
  EXPECT_TRUE(w.simFieldEnable().level());
}

TEST(SimWorld, NackFaultsFailTransfers) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  int rc = 0;
  w.setFault(Fault::ina228_nack, true);
  readReg(w, hw.ina228_address, ina228::MANUFACTURER_ID, 2, &rc);
  EXPECT_EQ(rc, EREMOTEIO);
  readReg(w, hw.ads1115_address, 1, 2, &rc);
  EXPECT_EQ(rc, 0);
  w.setFault(Fault::ina228_nack, false);
  w.setFault(Fault::ads1115_nack, true);
  readReg(w, hw.ina228_address, ina228::MANUFACTURER_ID, 2, &rc);
  EXPECT_EQ(rc, 0);
  readReg(w, hw.ads1115_address, 1, 2, &rc);
  EXPECT_EQ(rc, EREMOTEIO);
}

TEST(SimWorld, AnalogFaultsShiftTheAdsInputs) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  auto ch0 = [&] {
    // single-shot AIN0-GND at ±2.048 V, 860 SPS
    writeReg(w, hw.ads1115_address, 1, std::uint16_t(0x8000 | (4 << 12) | (2 << 9) | 0x100 | (7 << 5) | 3));
    w.advanceTo(w.now() + fromMs(2));
    const auto code = std::int16_t(readReg(w, hw.ads1115_address, 0, 2));
    return frontend::batteryVoltsFromAdc(hw.frontend, code * 2.048 / 32768.0);
  };
  const double v = ch0();
  EXPECT_NEAR(v, w.truth().plant.battery_v, 0.01);
  w.setFault(Fault::battery_v_offset, true, 1.5);
  EXPECT_NEAR(ch0(), v + 1.5, 0.02);
  w.setFault(Fault::battery_v_offset, false);
  w.setFault(Fault::battery_v_zero, true);
  EXPECT_NEAR(ch0(), 0.0, 1e-9);
}

TEST(SimWorld, RpmSignalLossDecaysWithTwoSecondCoupling) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  auto ch2 = [&] {
    writeReg(w, hw.ads1115_address, 1, std::uint16_t(0x8000 | (6 << 12) | (1 << 9) | 0x100 | (7 << 5) | 3));
    w.advanceTo(w.now() + fromMs(2));
    const auto code = std::int16_t(readReg(w, hw.ads1115_address, 0, 2));
    return frontend::rpmFromAdc(hw.frontend, code * 4.096 / 32768.0);
  };
  const double r0 = ch2();
  EXPECT_NEAR(r0, 1800.0, 2.0);
  w.setFault(Fault::rpm_signal_loss, true);
  w.advanceTo(w.now() + fromSec(2.0));
  EXPECT_NEAR(ch2(), r0 * std::exp(-1.0), 30.0);
  w.advanceTo(w.now() + fromSec(20.0));
  EXPECT_EQ(ch2(), 0.0);
}

TEST(SimWorld, FieldOpenFaultKillsOutput) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  w.simPwm().setEnabled(true);
  w.simPwm().setDutyPercent(80);
  w.fieldEnable().set(true);
  w.setFault(Fault::field_open, true);
  w.advanceTo(fromSec(2));
  EXPECT_EQ(w.truth().plant.alt_a, 0.0);
  EXPECT_FALSE(w.truth().field_on);
}

TEST(SimWorld, SameSeedSameNoise) {
  HardwareSettings hw;
  WorldConfig c;
  c.seed = 9;
  SimWorld a(c, hw), b(c, hw);
  for (int i = 1; i < 50; ++i) {
    a.advanceTo(fromMs(3 * i));
    b.advanceTo(fromMs(3 * i));
    EXPECT_EQ(readReg(a, hw.ina228_address, ina228::VSHUNT, 3), readReg(b, hw.ina228_address, ina228::VSHUNT, 3));
  }
}

TEST(SimClock, MaxSpeedAdvancesVirtualTime) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  SimClock clk(w, 0.0);
  clk.sleepUntil(fromSec(3600));
  EXPECT_EQ(clk.now(), fromSec(3600));
  EXPECT_EQ(w.now(), fromSec(3600));
}

}  // namespace
}  // namespace xr::sim
