#include "control/charging_stage.h"

#include <gtest/gtest.h>

#include "law_rig.h"
#include "stage_rig.h"

namespace xr {
namespace {

using test::StageRig;

TEST(ChargingStage, BulkToAbsorptionAfterHoldTimeNotBefore) {
  StageRig r;
  r.in.v = 14.46;  // >= Bulk - 0.05
  r.run(29.8);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
  EXPECT_FALSE(r.m.voltageControlActive());
  EXPECT_DOUBLE_EQ(r.m.ChargingVoltageTarget(r.p), 14.5);
  r.run(0.4);
  EXPECT_EQ(r.m.stage(), ChargeStage::ABSORPTION);
  EXPECT_TRUE(r.m.voltageControlActive());
  EXPECT_DOUBLE_EQ(r.m.ChargingVoltageTarget(r.p), 14.4);
}

TEST(ChargingStage, BulkBandHysteresisDipInsideBandKeepsTimer) {
  StageRig r;
  r.in.v = 14.46;
  r.run(20.0);
  r.in.v = 14.42;  // between Bulk-0.10 and Bulk-0.05: timer keeps running
  r.run(10.2);
  EXPECT_EQ(r.m.stage(), ChargeStage::ABSORPTION);
}

TEST(ChargingStage, BulkBandHysteresisDipBelowExitResetsTimer) {
  StageRig r;
  r.in.v = 14.46;
  r.run(20.0);
  r.in.v = 14.39;  // below Bulk - 0.10: clears
  r.run(0.1);
  r.in.v = 14.46;
  r.run(20.0);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
  r.run(10.2);
  EXPECT_EQ(r.m.stage(), ChargeStage::ABSORPTION);
}

TEST(ChargingStage, TailCurrentExitAfterAbsorptionCompleteTime) {
  StageRig r;
  r.toAbsorption();
  r.in.Bcur = r.p.TailCurrent_A;  // at the threshold counts
  r.run(29.8);
  EXPECT_EQ(r.m.stage(), ChargeStage::ABSORPTION);
  r.run(0.4);
  EXPECT_EQ(r.m.stage(), ChargeStage::FLOAT);
  EXPECT_DOUBLE_EQ(r.m.ChargingVoltageTarget(r.p), 13.5);
}

TEST(ChargingStage, TailExitRestartsWhenCurrentRisesAgain) {
  StageRig r;
  r.toAbsorption();
  r.in.Bcur = 1.0;
  r.run(20.0);
  r.in.Bcur = 10.0;
  r.run(0.1);
  r.in.Bcur = 1.0;
  r.run(20.0);
  EXPECT_EQ(r.m.stage(), ChargeStage::ABSORPTION);
}

TEST(ChargingStage, TailExitSuppressedWhileThermallyConstrained) {
  StageRig r;
  r.toAbsorption();
  r.in.Bcur = 1.0;
  r.in.thermalPenaltyAmps = 10.0;  // > 2 A
  r.in.uTargetAmps = 6.0;          // <= 2 x TailCurrent_A (8 A)
  r.run(60.0);
  EXPECT_EQ(r.m.stage(), ChargeStage::ABSORPTION);
  EXPECT_TRUE(r.m.tailSuppressedByThermal());
  r.in.thermalPenaltyAmps = 0.0;  // constraint clears: tail detection resumes
  r.run(30.2);
  EXPECT_EQ(r.m.stage(), ChargeStage::FLOAT);
}

TEST(ChargingStage, AbsorptionTimeout) {
  StageRig r;
  r.p.AbsorptionTimeoutMs = 120000;
  r.toAbsorption();
  r.in.Bcur = 30.0;  // never reaches tail
  r.run(119.5);
  EXPECT_EQ(r.m.stage(), ChargeStage::ABSORPTION);
  r.run(0.6);
  EXPECT_EQ(r.m.stage(), ChargeStage::FLOAT);
}

TEST(ChargingStage, UseFloatZeroGoesToIdleAndIdleDisablesCharging) {
  StageRig r;
  r.p.UseFloat = 0;
  r.toAbsorption();
  r.in.Bcur = 1.0;
  r.run(30.2);
  EXPECT_EQ(r.m.stage(), ChargeStage::IDLE);
  EXPECT_FALSE(r.m.chargingEnabled());
}

TEST(ChargingStage, UseFloatClearedWhileInFloatGoesToIdleAtOnce) {
  StageRig r;
  r.toFloat();
  r.p.UseFloat = 0;
  r.run(0.1);
  EXPECT_EQ(r.m.stage(), ChargeStage::IDLE);
}

TEST(ChargingStage, RebulkOnVoltageAfterMinFloatTimeAndDebounce) {
  StageRig r;
  r.toFloat();
  r.in.v = 12.8;  // below RebulkVoltage from the start of float
  r.run(r.p.MinFloatTime / 1000.0 + r.p.rebulkDebounceTime / 1000.0 - 0.5);
  EXPECT_EQ(r.m.stage(), ChargeStage::FLOAT);
  r.run(0.7);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
}

TEST(ChargingStage, RebulkOnDischargeCurrent) {
  StageRig r;
  r.toFloat();
  r.run(r.p.MinFloatTime / 1000.0);
  r.in.Bcur = -(r.p.RebulkCurrent_A + 1.0);
  r.run(r.p.rebulkDebounceTime / 1000.0 - 0.5);
  EXPECT_EQ(r.m.stage(), ChargeStage::FLOAT);
  r.run(0.7);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
}

TEST(ChargingStage, RebulkDebounceRestartsWhenConditionClears) {
  StageRig r;
  r.toFloat();
  r.run(r.p.MinFloatTime / 1000.0);
  r.in.v = 12.8;
  r.run(50.0);
  r.in.v = 13.2;
  r.run(0.1);
  r.in.v = 12.8;
  r.run(50.0);
  EXPECT_EQ(r.m.stage(), ChargeStage::FLOAT);
}

TEST(ChargingStage, FloatRebulksUnconditionallyAfter12Hours) {
  StageRig r;
  r.toFloat();
  r.in.Bcur = 0.0;
  r.run(43200.0 - 1.0);
  EXPECT_EQ(r.m.stage(), ChargeStage::FLOAT);
  r.run(1.2);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
}

TEST(ChargingStage, SocAtOrAboveBlockThresholdBlocksRebulk) {
  StageRig r;
  r.toFloat();
  r.in.socValid = true;
  r.in.SOC_percent = r.p.SOC_BlockRebulk_percent;
  r.in.v = 12.0;
  r.run(r.p.MinFloatTime / 1000.0 + r.p.rebulkDebounceTime / 1000.0 + 5.0);
  EXPECT_EQ(r.m.stage(), ChargeStage::FLOAT);
  EXPECT_TRUE(r.m.rebulkBlockedBySoc());
}

TEST(ChargingStage, SocAtOrBelowAllowThresholdRebulksEvenAtGoodVoltage) {
  StageRig r;
  r.toFloat();
  r.in.socValid = true;
  r.in.SOC_percent = r.p.SOC_AllowRebulk_percent;
  r.in.v = 13.5;
  r.in.Bcur = 0.0;
  r.run(r.p.MinFloatTime / 1000.0 + r.p.rebulkDebounceTime / 1000.0 + 0.5);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
}

TEST(ChargingStage, SocBetweenThresholdsUsesVoltageRules) {
  StageRig r;
  r.toFloat();
  r.in.socValid = true;
  r.in.SOC_percent = 88.0;
  r.in.v = 13.5;
  r.in.Bcur = 0.0;
  r.run(r.p.MinFloatTime / 1000.0 + r.p.rebulkDebounceTime / 1000.0 + 5.0);
  EXPECT_EQ(r.m.stage(), ChargeStage::FLOAT);
  r.in.v = 12.8;
  r.run(r.p.rebulkDebounceTime / 1000.0 + 0.5);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
}

TEST(ChargingStage, IdleRebulksOnSagLikeFloat) {
  StageRig r;
  r.p.UseFloat = 0;
  r.toAbsorption();
  r.in.Bcur = 1.0;
  r.run(30.2);
  ASSERT_EQ(r.m.stage(), ChargeStage::IDLE);
  r.in.v = 12.5;
  r.run(r.p.MinFloatTime / 1000.0 + r.p.rebulkDebounceTime / 1000.0 + 0.5);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
}

TEST(ChargingStage, SuppressedHoldsStageAndTimers) {
  StageRig r;
  r.in.v = 14.5;
  r.in.suppressed = true;
  r.run(120.0);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
  r.in.suppressed = false;  // timer starts afresh, not from the suppressed time
  r.run(29.0);
  EXPECT_EQ(r.m.stage(), ChargeStage::BULK);
}

TEST(ChargingStage, SuppressedInOverrideModesThroughTheControlLaw) {
  for (int mode = 0; mode < 3; ++mode) {
    test::LawRig rig;
    rig.p.bulkVoltageHoldMs = 1000;
    rig.plant.Vocv = 14.6;  // at bulk voltage from the start
    if (mode == 0) rig.p.MaintainMode = 1;
    if (mode == 1) rig.p.TargetVoltageMode = 1;
    if (mode == 2) rig.p.CVTuningMode = 1;
    rig.start();
    rig.run(5.0);
    EXPECT_EQ(rig.law.stages().stage(), ChargeStage::BULK) << "override " << mode;
  }
}

TEST(ChargingStage, BulkVoltageCeilingHoldsBulkTargetWhileTheHoldTimerRuns) {
  test::LawRig rig;
  rig.p.bulkVoltageHoldMs = 600000;  // stays in BULK for the whole test
  rig.plant.Vocv = 14.3;
  rig.plant.R = 0.008;
  rig.plant.voltsPerAmpSec = 0.002;  // a small bank: 50 A would reach 14.8 V in seconds
  rig.start();
  double vmax = 0.0;
  for (int i = 0; i < 60 * 400; ++i) {
    rig.tick();
    vmax = std::max(vmax, rig.plant.V());
  }
  EXPECT_EQ(rig.law.stages().stage(), ChargeStage::BULK);
  EXPECT_TRUE(rig.law.bulkVoltageLimitActive());
  EXPECT_TRUE(rig.law.voltageControlActive());
  EXPECT_LT(vmax, rig.p.BulkVoltage + 0.1);  // never near the 14.8 V hard shutdown
  EXPECT_NEAR(rig.plant.V(), rig.p.BulkVoltage, 0.05);
}

TEST(ChargingStage, BulkVoltageCeilingIdleFarBelowBulk) {
  test::LawRig rig;
  rig.start();
  rig.run(5.0);
  EXPECT_FALSE(rig.law.bulkVoltageLimitActive());
  EXPECT_FALSE(rig.law.voltageControlActive());
}

// Ours (docs/deviations.md "Return to AUTO"): back in AUTO within
// StageResumeMaxSec the stage it left resumes; later, or with 0, BULK.
TEST(ChargingStage, EnterSysAutoResumesAfterAShortAbsence) {
  test::LawRig rig;
  rig.p.bulkVoltageHoldMs = 1000;
  rig.plant.Vocv = 14.6;
  rig.start();
  rig.run(2.0);
  ASSERT_EQ(rig.law.stages().stage(), ChargeStage::ABSORPTION);
  rig.law.enterSysOff();
  rig.now += fromSec(rig.p.StageResumeMaxSec);  // exactly at the limit: still resumes
  rig.law.enterSysAuto(rig.sensors(), rig.p);
  EXPECT_EQ(rig.law.stages().stage(), ChargeStage::ABSORPTION);
}

TEST(ChargingStage, EnterSysAutoStartsInBulkAfterALongAbsence) {
  test::LawRig rig;
  rig.p.bulkVoltageHoldMs = 1000;
  rig.plant.Vocv = 14.6;
  rig.start();
  rig.run(2.0);
  ASSERT_EQ(rig.law.stages().stage(), ChargeStage::ABSORPTION);
  rig.law.enterSysOff();
  rig.now += fromSec(rig.p.StageResumeMaxSec + 0.01);
  rig.law.enterSysAuto(rig.sensors(), rig.p);
  EXPECT_EQ(rig.law.stages().stage(), ChargeStage::BULK);
  rig.run(2.0);  // and fast-forwards again when the battery is already up
  EXPECT_EQ(rig.law.stages().stage(), ChargeStage::ABSORPTION);
}

TEST(ChargingStage, StageResumeZeroKeepsTheSeedsAlwaysBulk) {
  test::LawRig rig;
  rig.p.bulkVoltageHoldMs = 1000;
  rig.p.StageResumeMaxSec = 0.0;
  rig.plant.Vocv = 14.6;
  rig.start();
  rig.run(2.0);
  ASSERT_EQ(rig.law.stages().stage(), ChargeStage::ABSORPTION);
  rig.law.enterSysOff();
  rig.law.enterSysAuto(rig.sensors(), rig.p);
  EXPECT_EQ(rig.law.stages().stage(), ChargeStage::BULK);
}

}  // namespace
}  // namespace xr
