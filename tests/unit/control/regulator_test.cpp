#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "control/telemetry.h"
#include "params/derived.h"
#include "reg_rig.h"

namespace xr {
namespace {

bool hasEvent(const Outputs& o, EventCode c) {
  for (std::size_t k = 0; k < o.events.count; ++k)
    if (o.events.items[k].code == c) return true;
  return false;
}

TEST(Regulator, StartsInAutoBulkAndTurnsTheFieldOnWithHealthySensors) {
  test::RegRig r;
  const Outputs& first = r.tick();
  EXPECT_TRUE(hasEvent(first, EventCode::ModeChanged));
  const int firstOn = hasEvent(first, EventCode::FieldOn) ? 1 : 0;
  EXPECT_EQ(r.run(2.0, EventCode::FieldOn) + firstOn, 1);
  const Outputs& o = *r.out;
  EXPECT_EQ(o.telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  EXPECT_EQ(o.telemetry.stage, ChargeStage::BULK);
  EXPECT_EQ(o.telemetry.reason, Reason::NONE);
  EXPECT_TRUE(o.fieldEnable);
  EXPECT_TRUE(o.inaFastMode);
  EXPECT_GT(o.dutyPct, 0.0);
  EXPECT_DOUBLE_EQ(o.inaBovlVolts, voltageHardwareLimit(r.p));
  EXPECT_DOUBLE_EQ(o.telemetry.target_v, r.p.BulkVoltage);
  EXPECT_DOUBLE_EQ(o.telemetry.target_a, 50.0);  // cap table at 2000 RPM
  EXPECT_GT(o.telemetry.setpoint_a, 0.0);
  EXPECT_DOUBLE_EQ(o.telemetry.duty_pct, o.dutyPct);
  EXPECT_EQ(o.telemetry.control.sysMode, SysMode::SYS_MODE_AUTO);
}

TEST(Regulator, ClosedLoopReachesTheCapCurrent) {
  test::RegRig r;
  r.run(30.0);
  EXPECT_NEAR(r.plant.Ialt, 50.0, 1.0);
  EXPECT_NEAR(r.out->telemetry.alt_a, r.plant.Ialt, 1.0);
}

TEST(Regulator, RpmGateIsAnImmediateCutWithControlSideResets) {
  test::RegRig r;
  r.run(5.0);
  ASSERT_TRUE(r.out->fieldEnable);
  r.rpm = 50.0;  // below MinRPMForField
  const Outputs& o = r.tick();
  EXPECT_FALSE(o.fieldEnable);
  EXPECT_DOUBLE_EQ(o.dutyPct, 0.0);
  EXPECT_TRUE(hasEvent(o, EventCode::FieldOff));
  EXPECT_EQ(o.telemetry.reason, Reason::REASON_RPM_LOW);
  EXPECT_EQ(o.telemetry.control.sysMode, SysMode::SYS_MODE_FAULT);
  EXPECT_DOUBLE_EQ(o.telemetry.control.setpointLimited, 0.0);
  EXPECT_DOUBLE_EQ(o.telemetry.control.innerTermI, 0.0);
}

TEST(Regulator, RestartAfterRpmGateIsBumplessFromZero) {
  test::RegRig r;
  r.run(5.0);
  r.rpm = 50.0;
  r.run(1.0);
  r.rpm = 2000.0;
  r.run(0.1);
  EXPECT_TRUE(r.out->fieldEnable);
  EXPECT_LT(r.out->dutyPct, 10.0);  // slews up from the floor, no jump to the old duty
  EXPECT_TRUE(r.out->telemetry.control.inStartupRamp);
}

TEST(Regulator, ManualCommandDrivesDutyAndBadValueIsRejected) {
  test::RegRig r;
  r.run(1.0);
  EXPECT_FALSE(r.reg.command({CommandType::Manual, 150.0, false}));
  const Outputs& o1 = r.tick();
  EXPECT_TRUE(hasEvent(o1, EventCode::CommandRejected));
  EXPECT_TRUE(r.reg.command({CommandType::Manual, 20.0, false}));
  r.run(2.0);
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_NORMAL_MANUAL);
  EXPECT_NEAR(r.out->dutyPct, 20.0, 1e-9);
  EXPECT_TRUE(r.reg.command({CommandType::Auto, 0.0, false}));
  r.tick();
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  EXPECT_NEAR(r.out->dutyPct, 20.0, 0.5);  // bumpless
}

TEST(Regulator, OffCommandRampsDownAndCutsTheField) {
  test::RegRig r;
  r.run(10.0);
  ASSERT_TRUE(r.out->fieldEnable);
  ASSERT_TRUE(r.reg.command({CommandType::Off, 0.0, false}));
  r.tick();
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_DISABLED_RAMP);
  EXPECT_EQ(r.out->telemetry.control.sysMode, SysMode::SYS_MODE_OFF);
  r.run(30.0);
  EXPECT_FALSE(r.out->fieldEnable);
  EXPECT_DOUBLE_EQ(r.out->dutyPct, 0.0);
  EXPECT_FALSE(r.out->inaFastMode);
}

TEST(Regulator, LimpHomeHoldsThirtyPercent) {
  test::RegRig r;
  r.run(1.0);
  ASSERT_TRUE(r.reg.command({CommandType::LimpHome, 0.0, false}));
  const int logs = r.run(31.0, EventCode::LimpHomeActive);
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_LIMP_HOME);
  EXPECT_DOUBLE_EQ(r.out->dutyPct, 30.0);
  EXPECT_EQ(logs, 2);
  ASSERT_TRUE(r.reg.command({CommandType::LimpHomeOff, 0.0, false}));
  r.tick();
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
}

TEST(Regulator, HoldsPidAndDutyWhenCh1IsNotFresh) {
  test::RegRig r;
  r.run(3.0);
  const double duty = r.out->dutyPct;
  const double integ = r.out->telemetry.control.innerTermI;
  r.ch1Fresh = false;
  r.tick();
  r.tick();
  EXPECT_DOUBLE_EQ(r.out->dutyPct, duty);
  EXPECT_DOUBLE_EQ(r.out->telemetry.control.innerTermI, integ);
  EXPECT_TRUE(r.out->fieldEnable);
}

TEST(Regulator, BulkAbsorptionFloatThroughTheWholeRegulator) {
  Params p;
  p.bulkVoltageHoldMs = 5000;
  p.absorptionCompleteTime = 5000;
  test::RegRig r(p);
  r.plant.Vocv = 14.2;
  r.plant.VocvMax = 14.38;  // the bank fills just under absorption: current tails off
  int stageChanges = r.run(400.0, EventCode::StageChanged);
  EXPECT_EQ(r.out->telemetry.stage, ChargeStage::FLOAT);
  EXPECT_EQ(stageChanges, 2);
  EXPECT_DOUBLE_EQ(r.out->telemetry.target_v, p.FloatVoltage);
  EXPECT_TRUE(r.out->telemetry.control.voltageControlActive);
  // The full bank sits at float: the field rests or the CV loop asks for
  // only the little current that holds the float voltage.
  EXPECT_GT(r.plant.V(), p.FloatVoltage - p.FieldRestWakeV - 0.02);
  EXPECT_LT(r.out->telemetry.setpoint_a, 3.0);
}

TEST(Regulator, UseFloatZeroEndsInIdleWithTheFieldOff) {
  Params p;
  p.bulkVoltageHoldMs = 5000;
  p.absorptionCompleteTime = 5000;
  p.UseFloat = 0;
  test::RegRig r(p);
  r.plant.Vocv = 14.2;
  r.plant.VocvMax = 14.38;
  r.run(400.0);
  EXPECT_EQ(r.out->telemetry.stage, ChargeStage::IDLE);
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_DISABLED_RAMP);
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_IDLE_STAGE);
  EXPECT_FALSE(r.out->fieldEnable);
  EXPECT_FALSE(r.out->telemetry.alarm);  // disabled, not a fault
}

TEST(Regulator, CommandsForwardToBatteryAndCheckLegality) {
  test::RegRig r;
  r.run(0.5);
  EXPECT_TRUE(r.reg.command({CommandType::SetSoc, 42.0, false}));
  r.tick();
  EXPECT_NEAR(r.out->telemetry.soc_pct, 42.0, 0.5);
  EXPECT_FALSE(r.reg.command({CommandType::SetSoc, 140.0, false}));
  EXPECT_TRUE(r.reg.command({CommandType::ResetAltZero, 0.0, false}));
  EXPECT_TRUE(r.reg.command({CommandType::ResetSocGain, 0.0, false}));
  EXPECT_TRUE(r.reg.command({CommandType::ReenableField, 0.0, false}));
  EXPECT_TRUE(r.reg.command({CommandType::ResetAlarmLatch, 0.0, false}));
  EXPECT_TRUE(r.reg.command({CommandType::WeatherMode, 0.0, true}));
  EXPECT_FALSE(r.reg.command({CommandType::TuningCommit, 0.0, false}));    // TuningMode off
  EXPECT_FALSE(r.reg.command({CommandType::CvTuningCommit, 0.0, false}));  // CVTuningMode off
  EXPECT_TRUE(r.reg.command({CommandType::SystemIdStart, 0.0, false}));    // AUTO with the field on
  r.tick();
  EXPECT_TRUE(r.out->telemetry.control.sysIDRunning);
  EXPECT_EQ(r.out->telemetry.control.govMode, GovMode::GOV_BYPASS_SLEW);
}

TEST(Regulator, WeatherModeDisablesChargingOnlyWhenEnabled) {
  Params p;
  p.weatherModeEnabled = 1;
  test::RegRig r(p);
  r.run(0.5);
  r.reg.command({CommandType::SetSoc, 80.0, false});
  r.reg.command({CommandType::WeatherMode, 0.0, true});
  r.tick();
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_DISABLED_RAMP);
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_WEATHER_MODE);
}

// The SoC floor (docs/deviations.md "Weather mode's SoC floor"): at
// WeatherModeMinSoC the sun may charge, just below it the alternator does.
TEST(Regulator, WeatherModeRestsTheAlternatorAtWeatherModeMinSoC) {
  Params p;
  p.weatherModeEnabled = 1;
  p.WeatherModeMinSoC = 50.0;
  test::RegRig r(p);
  r.run(0.5);
  r.reg.command({CommandType::SetSoc, 50.0, false});
  r.reg.command({CommandType::WeatherMode, 0.0, true});
  r.tick();
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_WEATHER_MODE);
}

TEST(Regulator, WeatherModeChargesJustBelowWeatherModeMinSoCAndWhenTheSocDrops) {
  Params p;
  p.weatherModeEnabled = 1;
  p.WeatherModeMinSoC = 50.0;
  test::RegRig r(p);
  r.run(0.5);
  r.reg.command({CommandType::SetSoc, 49.9, false});
  r.reg.command({CommandType::WeatherMode, 0.0, true});
  r.run(0.5);
  EXPECT_NE(r.out->telemetry.reason, Reason::REASON_WEATHER_MODE);
  EXPECT_NE(r.out->telemetry.mode, FieldControlMode::MODE_DISABLED_RAMP);
  r.reg.command({CommandType::SetSoc, 70.0, false});
  r.tick();
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_WEATHER_MODE);
  r.reg.command({CommandType::SetSoc, 30.0, false});  // the battery ran down under a sunny forecast
  r.run(0.5);
  EXPECT_NE(r.out->telemetry.reason, Reason::REASON_WEATHER_MODE);
  EXPECT_NE(r.out->telemetry.mode, FieldControlMode::MODE_DISABLED_RAMP);
}

TEST(Regulator, TelemetryHasEveryDesignColumn) {
  test::RegRig r;
  r.run(0.1);
  std::set<std::string> names;
  visitTelemetryColumns(r.out->telemetry, 0,
                        [&](std::string_view n, const ColumnValue&) { names.emplace(n); });
  for (const char* c : {"t_s",
                        "mode",
                        "stage",
                        "reason",
                        "ibv_v",
                        "battery_v",
                        "bcur_a",
                        "alt_a",
                        "rpm",
                        "temp_f",
                        "duty_pct",
                        "field_enable",
                        "setpoint_a",
                        "target_a",
                        "target_v",
                        "thermal_penalty_a",
                        "fast_ov_active",
                        "soc_pct",
                        "alarm",
                        "charged_wh_lifetime",
                        "alt_charged_wh_lifetime",
                        "bms_cvl_v",
                        "bms_ccl_a",
                        "bms_soc_pct",
                        "bms_state"})
    EXPECT_TRUE(names.count(c)) << c;
  EXPECT_NEAR(r.out->telemetry.ibv_v, r.plant.V(), 0.05);
  EXPECT_DOUBLE_EQ(r.out->telemetry.rpm, 2000.0);
  EXPECT_DOUBLE_EQ(r.out->telemetry.temp_f, 100.0);
}

TEST(Regulator, AutoZeroRunsBeforeControlAndHoldsTheFieldLow) {
  Params p;
  p.AutoAltCurrentZero = 1;
  test::RegRig r(p);
  r.run(3.0);
  ASSERT_TRUE(r.out->fieldEnable);
  r.tempF = 125.0;  // moved >= 20 degF since the baseline: auto-zero triggers
  r.tick();
  EXPECT_FALSE(r.out->fieldEnable);  // LOW within the same tick (no ramp)
  EXPECT_DOUBLE_EQ(r.out->dutyPct, 0.0);
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_LOCKOUT_RAMP);
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_AUTO_ZERO);
  r.run(5.0);
  EXPECT_FALSE(r.out->fieldEnable);
  r.run(40.0);  // measurement over: charging resumes
  EXPECT_TRUE(r.out->fieldEnable);
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
}

TEST(Regulator, NanSensorsGiveSafeStateNotCrash) {
  test::RegRig r;
  r.run(2.0);
  Inputs in = r.inputs();
  for (int i = 0; i < 4000; ++i) {
    in.now += fromUs(2500);
    in.IBV = {std::nan(""), 0, false};
    in.BatteryV = {std::nan(""), 0, false};
    in.altCurrentRaw = {std::nan(""), 0, false};
    r.reg.step(in);
  }
  EXPECT_FALSE(r.reg.outputs().fieldEnable);
  EXPECT_DOUBLE_EQ(r.reg.outputs().dutyPct, 0.0);
}

}  // namespace
}  // namespace xr
