// After absorption, a bank that rests (docs/batteries.md "After absorption",
// docs/deviations.md "LiFePO4 rests at zero battery current"): the re-bulk
// on a counted discharge, the full charge the tail exit declares, IDLE
// resuming after a short absence, and the regulator holding the battery
// current at zero in IDLE while the alternator carries the house load.
#include <gtest/gtest.h>

#include <cmath>

#include "control/charging_stage.h"
#include "reg_rig.h"
#include "stage_rig.h"

namespace xr {
namespace {

// A LiFePO4-like bank of 200 Ah that has just finished its absorption.
struct RestRig : test::StageRig {
  RestRig() {
    p.BulkVoltage = p.AbsorptionVoltage = 14.2;
    p.UseFloat = 0;
    p.IdleZeroCurrent = 1;
    p.RebulkDischarge_percent = 10.0;  // 20 Ah of 200 Ah
    p.BatteryCapacity_Ah = 200.0;
    in.v = 14.2;
    run(p.bulkVoltageHoldMs / 1000.0 + 0.2);
    in.Bcur = 1.0;  // the tail
    run(p.absorptionCompleteTime / 1000.0 + 0.2);
    in.v = 13.35;
  }
};

TEST(ChargingStage, RestRebulksOnCountedDischargeNotOnTheCurrent) {
  RestRig r;
  ASSERT_EQ(r.m.stage(), ChargeStage::IDLE);
  r.in.Bcur = -60.0;  // far over RebulkCurrent_A: 20 Ah are out after 1200 s
  r.run(1199.0);      // 19.98 Ah: not yet a real discharge
  EXPECT_EQ(r.m.stage(), ChargeStage::IDLE);
  EXPECT_NEAR(r.m.restDischargedAh(), 19.983, 0.01);
  r.run(60.0);  // 20 Ah reached at 1200 s; the debounce runs to 1260 s
  EXPECT_EQ(r.m.stage(), ChargeStage::IDLE);
  r.run(1.5);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
}

TEST(ChargingStage, RestDischargeCountsTheChargeBack) {
  RestRig r;
  // A fridge cycling 30 A for 10 min, then 10 min of the alternator putting
  // it back: never 20 Ah out, so the bank is never re-absorbed.
  for (int cycle = 0; cycle < 12; ++cycle) {
    r.in.Bcur = -30.0;
    r.run(600.0);
    r.in.Bcur = 30.0;
    r.run(600.0);
  }
  EXPECT_EQ(r.m.stage(), ChargeStage::IDLE);
  EXPECT_LT(r.m.restDischargedAh(), 5.01);
}

TEST(ChargingStage, RestVoltageSagStillRebulks) {
  RestRig r;
  r.in.Bcur = 0.0;
  r.in.v = 12.8;  // under RebulkVoltage: a bank run down by something else
  r.run(r.p.MinFloatTime / 1000.0 + r.p.rebulkDebounceTime / 1000.0 + 0.5);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
}

TEST(ChargingStage, LeadAcidKeepsTheDischargeCurrentRule) {
  RestRig r;
  r.p.RebulkDischarge_percent = 0.0;  // the catalogue default (and every lead-acid profile)
  r.in.Bcur = -(r.p.RebulkCurrent_A + 1.0);
  r.run(r.p.MinFloatTime / 1000.0 + r.p.rebulkDebounceTime / 1000.0 + 0.5);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
}

TEST(ChargingStage, TailExitIsACompletedChargeTimeoutIsNot) {
  StageInputs in;
  Params p;
  p.bulkVoltageHoldMs = 1000;
  p.absorptionCompleteTime = 1000;
  p.AbsorptionTimeoutMs = 60000;
  ChargingStageMachine m;
  in.now = fromSec(10);
  in.v = 14.5;
  in.Bcur = 1.0;
  in.uTargetAmps = 50.0;
  m.resetToBulk(in.now);
  int completions = 0;
  for (int i = 0; i < 50; ++i) {
    in.now += fromMs(100);
    m.updateChargingStage(in, p);
    completions += m.completedOnTail();
  }
  EXPECT_EQ(m.stage(), ChargeStage::FLOAT);
  EXPECT_EQ(completions, 1);  // once, on the call that left absorption
  // Ended by its timeout: not a full charge.
  ChargingStageMachine t;
  t.resetToBulk(in.now);
  in.Bcur = 30.0;
  completions = 0;
  for (int i = 0; i < 700; ++i) {
    in.now += fromMs(100);
    t.updateChargingStage(in, p);
    completions += t.completedOnTail();
  }
  EXPECT_EQ(t.stage(), ChargeStage::FLOAT);
  EXPECT_EQ(completions, 0);
}

TEST(ChargingStage, IdleResumesAfterAShortAbsence) {
  RestRig r;
  ASSERT_EQ(r.m.stage(), ChargeStage::IDLE);
  EXPECT_TRUE(r.m.resumeOrBulk(r.in.now, fromSec(r.p.StageResumeMaxSec), r.p));
  EXPECT_EQ(r.m.stage(), ChargeStage::IDLE);
  EXPECT_FALSE(r.m.resumeOrBulk(r.in.now, fromSec(r.p.StageResumeMaxSec + 0.01), r.p));
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
}

// The whole regulator: a full bank in IDLE with a 10 A house load.
Params idleParams(bool zeroCurrent) {
  Params p;
  p.UseFloat = 0;
  p.IdleZeroCurrent = zeroCurrent;
  p.bulkVoltageHoldMs = 1000;
  p.absorptionCompleteTime = 1000;
  p.BulkVoltage = p.AbsorptionVoltage = 14.2;
  p.FloatVoltage = 13.5;
  return p;
}

struct IdleRig : test::RegRig {
  explicit IdleRig(bool zeroCurrent) : RegRig(idleParams(zeroCurrent)) {
    plant.Vocv = 14.3;  // full: the bank is at its target and takes no current
    plant.VocvMax = 14.3;
    plant.house = 10.0;
  }
};

TEST(IdleZeroCurrent, TheAlternatorCarriesTheHouseLoadWhileTheBankRests) {
  IdleRig r(true);
  r.run(20.0);
  ASSERT_EQ(r.out->telemetry.stage, ChargeStage::IDLE);
  r.plant.Vocv = 13.35;  // the bank relaxes to its rest voltage
  r.plant.VocvMax = 14.3;
  r.run(60.0);
  EXPECT_EQ(r.out->telemetry.stage, ChargeStage::IDLE);
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  EXPECT_TRUE(r.out->fieldEnable);
  EXPECT_NEAR(r.plant.Ibat(), 0.0, 1.5);  // the bank neither charged nor discharged
  EXPECT_NEAR(r.plant.Ialt, 10.0, 1.5);   // the house load is the alternator's
}

TEST(IdleZeroCurrent, OffTheFieldRestsInIdleAsTheSeed) {
  IdleRig r(false);
  r.run(20.0);
  ASSERT_EQ(r.out->telemetry.stage, ChargeStage::IDLE);
  r.plant.Vocv = 13.35;
  r.run(60.0);
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_DISABLED_RAMP);
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_IDLE_STAGE);
  EXPECT_FALSE(r.out->fieldEnable);
  EXPECT_NEAR(r.plant.Ibat(), -10.0, 0.5);  // the bank carries the house
}

}  // namespace
}  // namespace xr
