// A new Params reaches every loop on the next tick (the PID gains, the
// temperature PID's setpoint, the RPM tables), and mode selection follows
// every snapshot input on its tick.
#include <gtest/gtest.h>

#include "control/thermal_derate.h"
#include "reg_rig.h"

namespace xr {
namespace {

// The current PID's gains are applied once per setParams: a new PidKp must
// reach the P term of the next compute.
TEST(ControlSetParams, NewPidGainsReachTheCurrentLoop) {
  test::RegRig rig;
  rig.run(5.0);
  ASSERT_EQ(rig.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  ASSERT_NE(rig.out->telemetry.control.innerTermP, 0.0);
  Params q = rig.p;
  q.PidKp = 0.0;
  rig.reg.setParams(q);
  rig.run(0.1);
  EXPECT_EQ(rig.out->telemetry.control.innerTermP, 0.0);
}

// The temperature PID's setpoint is configured once per setParams: lowering
// TemperatureLimitF under the present temperature must start a penalty.
TEST(ControlSetParams, NewTemperatureLimitReachesTheThermalLoop) {
  test::RegRig rig;
  rig.tempF = 140.0;
  rig.run(12.0);
  ASSERT_EQ(rig.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  ASSERT_EQ(rig.out->telemetry.control.thermalPenaltyAmps_d, 0.0);
  Params q = rig.p;
  q.TemperatureLimitF = 139.0;  // T1 at 141 degF: no protection trips at 140
  rig.reg.setParams(q);
  rig.run(12.0);
  EXPECT_EQ(rig.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  EXPECT_GT(rig.out->telemetry.control.thermalPenaltyAmps_d, 0.0);
}

// The RPM lookups are kept while rpm repeats bit for bit (the rig's rpm is
// constant): new tables at the same rpm must still be read.
TEST(ControlSetParams, NewRpmTablesAreReadAtAnUnchangedRpm) {
  test::RegRig rig;
  rig.run(2.0);
  ASSERT_EQ(rig.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  const double before = rig.out->telemetry.control.rpmMinDuty;
  const double capBefore = rig.out->telemetry.control.I_cap;
  Params q = rig.p;
  q.rpmMinDutyTable.fill(before + 3.0);
  q.rpmMinDutyTableLo.fill(before + 3.0);
  q.rpmCapCurrentTable.fill(capBefore - 5.0);
  q.rpmCapCurrentTableLo.fill(capBefore - 5.0);
  rig.reg.setParams(q);
  rig.tick();
  EXPECT_EQ(rig.out->telemetry.control.rpmMinDuty, before + 3.0);
  EXPECT_EQ(rig.out->telemetry.control.I_cap, capBefore - 5.0);
}

// A changed rpm is looked up again, a repeated one gives the same values.
TEST(ControlSetParams, RpmLookupFollowsEveryChangeOfRpm) {
  test::RegRig rig;
  Params q = rig.p;
  q.rpmTableRPMPoints = {500, 1000, 1500, 2000, 2500, 3000, 3500, 4000, 4500, 5000};
  q.rpmCapCurrentTable = {10, 20, 30, 40, 50, 60, 70, 80, 90, 100};
  q.rpmCapCurrentTableLo = q.rpmCapCurrentTable;
  q.capLimitMode = 0;
  rig.reg.setParams(q);
  rig.rpm = 2250.0;
  rig.run(1.0);
  ASSERT_EQ(rig.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  EXPECT_DOUBLE_EQ(rig.out->telemetry.control.I_cap, 45.0);
  rig.rpm = 2750.0;
  rig.tick();
  EXPECT_DOUBLE_EQ(rig.out->telemetry.control.I_cap, 55.0);
  rig.tick();
  EXPECT_DOUBLE_EQ(rig.out->telemetry.control.I_cap, 55.0);
  rig.rpm = 2250.0;
  rig.tick();
  EXPECT_DOUBLE_EQ(rig.out->telemetry.control.I_cap, 45.0);
}

// ThermalDerate on its own: a Params change (here in place) is seen on the
// very next update; nothing derived from the Params is kept between calls.
TEST(ControlSetParams, ThermalDerateFollowsParamsChangedInPlace) {
  Params p;
  ThermalDerate t;
  ThermalInputs in;
  in.now = fromSec(1000.0);
  in.dtSec = 0.01;
  in.tempValid = true;
  in.TempToUse = 140.0;
  for (int i = 0; i < 1000; ++i) {
    in.now += fromSec(in.dtSec);
    in.tempFresh = i % 100 == 0;
    t.update(in, p);
  }
  ASSERT_EQ(t.penaltyTarget(), 0.0);
  p.TemperatureLimitF = 130.0;
  for (int i = 0; i < 1000; ++i) {
    in.now += fromSec(in.dtSec);
    in.tempFresh = i % 100 == 0;
    t.update(in, p);
  }
  EXPECT_GT(t.penaltyTarget(), 0.0);
}

// Each operator input and a protection flag changes the mode on the very
// tick it changes, and changing it back restores AUTO.
TEST(ModeSelectionMemo, EverySnapshotInputChangesTheModeOnItsTick) {
  test::RegRig rig;
  rig.run(2.0);
  ASSERT_EQ(rig.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  auto stepWith = [&](auto change) {
    rig.now += fromSec(0.0025);
    Inputs in = rig.inputs();
    change(in);
    return rig.reg.step(in).telemetry.reason;
  };
  EXPECT_EQ(stepWith([](Inputs& in) { in.ignitionOn = false; }), Reason::REASON_IGNITION_OFF);
  EXPECT_EQ(stepWith([](Inputs&) {}), Reason::NONE);
  EXPECT_EQ(stepWith([](Inputs& in) { in.bmsChargeEnabled = false; }), Reason::REASON_BMS_DISABLED);
  EXPECT_EQ(stepWith([](Inputs&) {}), Reason::NONE);
  EXPECT_EQ(stepWith([](Inputs& in) { in.rpm.value = 0.0; }), Reason::REASON_RPM_LOW);
  EXPECT_EQ(rig.out->telemetry.mode, FieldControlMode::MODE_DISABLED_RAMP);
  EXPECT_EQ(stepWith([](Inputs&) {}), Reason::NONE);
  EXPECT_EQ(rig.reg.outputs().telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  rig.reg.command(Command{CommandType::Off});
  EXPECT_EQ(stepWith([](Inputs&) {}), Reason::REASON_SYS_OFF);
  rig.reg.command(Command{CommandType::Auto});
  EXPECT_EQ(stepWith([](Inputs&) {}), Reason::NONE);
  rig.reg.command(Command{CommandType::LimpHome});
  EXPECT_EQ(stepWith([](Inputs&) {}), Reason::REASON_LIMP_HOME);
  rig.reg.command(Command{CommandType::LimpHomeOff});
  EXPECT_EQ(stepWith([](Inputs&) {}), Reason::NONE);
}

}  // namespace
}  // namespace xr
