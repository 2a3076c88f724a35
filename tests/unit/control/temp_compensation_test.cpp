// Lead-acid temperature compensation and the battery temperature current cap
// through Regulator::step (docs/batteries.md): at the reference, at the clamp limits,
// just inside them, with a stale sample, and under the trip ceiling.
#include "control/temp_compensation.h"

#include <gtest/gtest.h>

#include "reg_rig.h"

namespace xr::test {
namespace {

Params agm() {
  Params p;
  p.BulkVoltage = 14.4;
  p.AbsorptionVoltage = 14.4;
  p.FloatVoltage = 13.3;
  p.BatteryCells = 6;
  p.TempCompMvPerCellC = -4.0;
  p.TempCompMinC = -10.0;
  p.TempCompMaxC = 50.0;
  return p;
}

TEST(TempCompensation, ZeroAtTheReferenceAndMinus4mVPerCellPerDegree) {
  const Params p = agm();
  EXPECT_DOUBLE_EQ(temperatureCompensationV(p, 25.0), 0.0);
  EXPECT_NEAR(temperatureCompensationV(p, 40.0), -0.36, 1e-12);  // 6 x -4 mV x 15 degC
  EXPECT_NEAR(temperatureCompensationV(p, 24.0), 0.024, 1e-12);
}

TEST(TempCompensation, TemperatureClampedAtTheConfiguredLimits) {
  const Params p = agm();
  EXPECT_NEAR(temperatureCompensationV(p, 50.0), -0.6, 1e-12);    // at the upper limit
  EXPECT_NEAR(temperatureCompensationV(p, 49.9), -0.5976, 1e-9);  // just inside
  EXPECT_NEAR(temperatureCompensationV(p, 60.0), -0.6, 1e-12);    // beyond: held
  EXPECT_NEAR(temperatureCompensationV(p, -10.0), 0.84, 1e-12);
  EXPECT_NEAR(temperatureCompensationV(p, -20.0), 0.84, 1e-12);
}

TEST(TempCompensation, StaleOrOffMeansUncompensated) {
  Params p = agm();
  EXPECT_DOUBLE_EQ(temperatureCompensationV(p, kNoValue), 0.0);
  p.TempCompMvPerCellC = 0.0;  // LiFePO4
  EXPECT_DOUBLE_EQ(temperatureCompensationV(p, 0.0), 0.0);
}

TEST(TempCompensation, ColdNeverRaisesATargetToTheTrip) {
  const Params p = agm();  // trip and INA limit 14.7 V: ceiling 14.5 V
  Params out;
  compensateTargets(p, temperatureCompensationV(p, -10.0), out);
  EXPECT_DOUBLE_EQ(out.AbsorptionVoltage, 14.5);
  EXPECT_DOUBLE_EQ(out.BulkVoltage, 14.5);
  EXPECT_NEAR(out.FloatVoltage, 13.3 + 0.84, 1e-9);
  compensateTargets(p, -0.36, out);
  EXPECT_NEAR(out.AbsorptionVoltage, 14.04, 1e-12);
}

// The whole Regulator with the battery temperature as the DS18B20 gives it.
struct TempRig : RegRig {
  double batteryC = 25.0;
  bool stale = false;
  TimeNs batteryStamp = 0;
  using RegRig::RegRig;
  const Outputs& step() {
    now += fromSec(0.0025);
    if (now - tempStamp >= fromSec(1.0)) tempStamp = now;
    if (!stale && now - batteryStamp >= fromSec(1.0)) batteryStamp = now;
    Inputs in = inputs();
    in.batteryTempSource = BatteryTempSource::ds18b20;
    in.batteryTempC = {batteryC, batteryStamp, batteryStamp == now};
    out = &reg.step(in);
    plant.advance(out->dutyPct, out->fieldEnable, 0.0025);
    return *out;
  }
  void run(double s) {
    for (long i = 0; i < std::lround(s / 0.0025); ++i) step();
  }
};

TEST(TempCompensation, TargetVShowsTheCompensatedTargetAndStaleFallsBack) {
  TempRig r(agm());
  r.batteryC = 40.0;
  r.run(2.0);
  EXPECT_NEAR(r.out->telemetry.target_v, 14.04, 1e-9);
  EXPECT_NEAR(r.out->telemetry.battery_temp_c, 40.0, 1e-12);
  r.batteryC = 25.0;
  r.run(2.0);
  EXPECT_NEAR(r.out->telemetry.target_v, 14.4, 1e-9);
  // Stale (no new sample for more than 20 s): uncompensated.
  r.batteryC = 40.0;
  r.run(2.0);
  r.stale = true;
  r.run(19.0);
  EXPECT_NEAR(r.out->telemetry.target_v, 14.04, 1e-9);
  r.run(2.0);
  EXPECT_NEAR(r.out->telemetry.target_v, 14.4, 1e-9);
}

TEST(TempCompensation, ColdLifepoBankGetsNoFieldAndACappedRampAboveZero) {
  Params p;
  p.BulkVoltage = p.AbsorptionVoltage = 14.2;
  p.FloatVoltage = 13.5;
  p.ChargeMinTempC = 0.0;
  p.ChargeFullCurrentTempC = 5.0;
  p.MaximumAllowedBatteryAmps = 40.0;
  TempRig r(p);
  r.batteryC = -5.0;
  r.run(10.0);
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_BATTERY_COLD);
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_DISABLED_RAMP);
  EXPECT_FALSE(r.out->fieldEnable);
  EXPECT_FALSE(r.out->buzzer);
  r.batteryC = 1.0;  // 20 % of the 40 A: an 8 A cap on the battery current
  r.run(20.0);
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  EXPECT_LE(r.plant.Ibat(), 8.0 + 0.5);
  EXPECT_GT(r.plant.Ibat(), 4.0);  // charging, not just carrying the house
  // The house load is served on top of the cap (docs/batteries.md).
  EXPECT_LE(r.out->telemetry.target_a, 8.0 + r.plant.house + 0.5);
  EXPECT_GT(r.out->telemetry.target_a, 8.0);
}

}  // namespace
}  // namespace xr::test
