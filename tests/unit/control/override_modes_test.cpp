#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "law_rig.h"
#include "params/constants.h"

namespace xr {
namespace {

TEST(MaintainMode, CeilingZeroCvAtBulkAndPidChasesZeroBatteryCurrent) {
  test::LawRig rig;
  rig.p.MaintainMode = 1;
  rig.plant.house = 20.0;  // the house draws 20 A: the alternator should supply it
  rig.start();
  rig.run(20.0);
  EXPECT_TRUE(rig.law.voltageControlActive());
  EXPECT_DOUBLE_EQ(rig.law.ChargingVoltageTarget(), rig.p.BulkVoltage);
  EXPECT_DOUBLE_EQ(rig.law.uTargetAmps(), 0.0);
  EXPECT_DOUBLE_EQ(rig.law.setpointLimited(), 0.0);
  EXPECT_DOUBLE_EQ(rig.law.currentPID().input, rig.plant.Ibat());  // Bcur feedback, not alternator amps
  EXPECT_NEAR(rig.plant.Ibat(), 0.0, 0.5);
  EXPECT_NEAR(rig.plant.Ialt, 20.0, 0.5);
}

TEST(TargetVoltageMode, HoldsTheUserSetpointWithCvForced) {
  test::LawRig rig;
  rig.p.TargetVoltageMode = 1;
  rig.p.TargetVoltageSetpoint = 13.6;
  rig.plant.Vocv = 13.55;
  rig.plant.VocvMax = 13.55;  // the bank's rest voltage stays just below target
  rig.start();
  rig.run(60.0);
  EXPECT_TRUE(rig.law.voltageControlActive());
  EXPECT_DOUBLE_EQ(rig.law.ChargingVoltageTarget(), 13.6);
  EXPECT_NEAR(rig.plant.V(), 13.6, 0.03);
}

// Ours: a short override resumes the stage it interrupted; a long one (over
// StageResumeMaxSec) restarts in BULK as the seed does.
TEST(TargetVoltageMode, ShortExitResumesTheStage) {
  test::LawRig rig;
  rig.p.bulkVoltageHoldMs = 500;
  rig.plant.Vocv = 14.6;
  rig.start();
  rig.run(1.0);
  ASSERT_EQ(rig.law.stages().stage(), ChargeStage::ABSORPTION);
  rig.p.TargetVoltageMode = 1;
  rig.run(0.1);
  rig.p.TargetVoltageMode = 0;
  rig.tick();
  EXPECT_EQ(rig.law.stages().stage(), ChargeStage::ABSORPTION);
}

TEST(TargetVoltageMode, LongExitResumesFromBulk) {
  test::LawRig rig;
  rig.p.bulkVoltageHoldMs = 500;
  rig.p.StageResumeMaxSec = 0.5;
  rig.plant.Vocv = 14.6;
  rig.start();
  rig.run(1.0);
  ASSERT_EQ(rig.law.stages().stage(), ChargeStage::ABSORPTION);
  rig.p.TargetVoltageMode = 1;
  rig.run(1.0);
  rig.p.TargetVoltageMode = 0;
  rig.tick();
  EXPECT_EQ(rig.law.stages().stage(), ChargeStage::BULK);
}

TEST(TuningMode, SquareWaveBetweenBaseAndBasePlusAmplitude) {
  test::LawRig rig;
  rig.p.TuningMode = 1;
  rig.p.waveAmplitude = 10.0;
  rig.p.wavePeriod = 4.0;
  rig.start();
  rig.run(1.0);
  EXPECT_DOUBLE_EQ(rig.law.uTargetAmps(), 5.0);
  EXPECT_FALSE(rig.law.voltageControlActive());
  rig.run(2.0);  // t = 3 s: HIGH half
  EXPECT_DOUBLE_EQ(rig.law.uTargetAmps(), 15.0);
  rig.run(2.0);  // t = 5 s: LOW again
  EXPECT_DOUBLE_EQ(rig.law.uTargetAmps(), 5.0);
}

TEST(TuningMode, ScoresOnlyWhenSetpointSlewsBelow1AperSecond) {
  test::LawRig rig;
  rig.p.TuningMode = 1;
  rig.p.wavePeriod = 8.0;
  rig.start();
  rig.run(0.004);
  EXPECT_FALSE(rig.law.tuning().scoringOpen());  // 3 A/s startup ramp: window closed
  rig.run(3.5);
  EXPECT_TRUE(rig.law.tuning().scoringOpen());
  EXPECT_GT(rig.law.tuning().scoredSec(), 0.5);
  EXPECT_LT(rig.law.tuning().scoredSec(), 3.5);
}

TEST(TuningMode, CommitKeepsTheLast50Records) {
  test::LawRig rig;
  rig.p.TuningMode = 1;
  rig.start();
  EXPECT_FALSE(rig.law.commitTuning(rig.now, rig.p));  // nothing scored yet
  rig.run(3.0);
  for (int i = 0; i < 55; ++i) {
    rig.p.PidKp = 0.1 + 0.01 * i;
    rig.run(1.0);
    ASSERT_TRUE(rig.law.commitTuning(rig.now, rig.p));
  }
  EXPECT_EQ(rig.law.tuning().logCount(), 50);
  EXPECT_NEAR(rig.law.tuning().record(0).PidKp, 0.1 + 0.01 * 5, 1e-12);  // oldest kept
  EXPECT_NEAR(rig.law.tuning().record(49).PidKp, 0.1 + 0.01 * 54, 1e-12);
  EXPECT_GE(rig.law.tuning().record(49).score, 0.0);
}

TEST(CvTuningMode, SquareWaveOnTargetAndOvershootCostsMoreThanUndershoot) {
  Params p;
  CvTuningModeRunner over, under;
  const TimeNs t0 = fromSec(10);
  // HIGH phase starts at cvWavePeriod/2 = 10 s.
  const TimeNs high = t0 + fromSec(11);
  over.target(t0, 14.0, p);
  under.target(t0, 14.0, p);
  EXPECT_NEAR(over.target(high, 14.0, p), 14.2, 1e-12);
  EXPECT_TRUE(over.highPhase());
  under.target(high, 14.0, p);
  for (int i = 0; i < 100; ++i) {
    over.score(14.2 + 0.1, 0.01, p);   // 100 mV over (75 mV beyond the free band)
    under.score(14.2 - 0.1, 0.01, p);  // 100 mV under
  }
  EXPECT_NEAR(over.currentScore(), p.cvKOvershoot * 0.075 * 0.075, 1e-9);
  EXPECT_NEAR(under.currentScore(), 0.1 * 0.1, 1e-9);
}

TEST(CvTuningMode, FirstMillivoltsOfHighOvershootAreFree) {
  Params p;
  CvTuningModeRunner r;
  r.target(0, 14.0, p);
  r.target(fromSec(11), 14.0, p);
  for (int i = 0; i < 10; ++i) r.score(14.2 + 0.02, 0.01, p);
  EXPECT_DOUBLE_EQ(r.currentScore(), 0.0);
}

TEST(CvTuningMode, HighTargetStaysUnderTheHardShutdownTrip) {
  Params p;  // BulkVoltage 14.5: trip 14.8, HIGH ceiling 14.6
  CvTuningModeRunner r;
  r.target(fromSec(0), 14.3, p);
  p.cvWaveAmplitudeV = 0.3;  // 14.6 exactly at the ceiling: allowed
  EXPECT_DOUBLE_EQ(r.target(fromSec(15), 14.3, p), 14.3 + 0.3);
  p.cvWaveAmplitudeV = 0.31;  // just over: held at the ceiling
  EXPECT_DOUBLE_EQ(r.target(fromSec(15), 14.3, p), 14.8 - k::CV_TUNING_TRIP_MARGIN_V);
  EXPECT_DOUBLE_EQ(r.target(fromSec(25), 14.3, p), 14.3);  // LOW phase untouched
}

TEST(CvTuningMode, LowPhaseUndershootGraceThenRamp) {
  Params p;
  CvTuningModeRunner r;
  r.target(fromSec(0), 14.0, p);
  r.target(fromSec(0.5), 14.0, p);
  r.score(13.9, 0.01, p);  // inside the 1 s grace: free
  EXPECT_DOUBLE_EQ(r.currentScore(), 0.0);
  r.target(fromSec(6.0), 14.0, p);  // 5 s into LOW: weight (6-1)/10 = 0.5
  r.score(13.9, 0.01, p);
  EXPECT_NEAR(r.currentScore(), 0.5 * 0.01 * 0.01 / 0.02, 1e-12);
}

TEST(CvTuningMode, SettleTimeCountsConsecutiveReadsInBand) {
  Params p;
  p.cvConsecutiveReads = 5;
  CvTuningModeRunner r;
  r.target(fromSec(0), 14.0, p);
  TimeNs t = fromSec(0);
  for (int i = 0; i < 100; ++i) {  // 10 ms ticks; in band from 0.5 s
    t += fromMs(10);
    r.target(t, 14.0, p);
    r.score(i < 50 ? 13.8 : 14.01, 0.01, p);
  }
  EXPECT_NEAR(r.lastSettleSec(), 0.55, 0.011);
}

TEST(CvTuningMode, DrivesTheLawTargetAndCommitsToLog) {
  test::LawRig rig;
  rig.p.CVTuningMode = 1;
  rig.start();
  rig.run(1.0);
  EXPECT_TRUE(rig.law.voltageControlActive());
  EXPECT_DOUBLE_EQ(rig.law.ChargingVoltageTarget(), rig.p.BulkVoltage);
  rig.run(10.0);
  // Ours: the HIGH target stays CV_TUNING_TRIP_MARGIN_V under the hard
  // shutdown (14.8 V): 14.5 + 0.2 is held at 14.6.
  EXPECT_DOUBLE_EQ(rig.law.ChargingVoltageTarget(),
                   std::min(rig.p.BulkVoltage + rig.p.cvWaveAmplitudeV, 14.8 - k::CV_TUNING_TRIP_MARGIN_V));
  EXPECT_TRUE(rig.law.commitCvTuning(rig.now, rig.p));
  EXPECT_EQ(rig.law.cvTuning().logCount(), 1);
}

// Not set up (config/setup_pending.h): the running layer sets the charge
// ceiling and lowers the values; the core clamps every target to the
// ceiling too, so a value that got past the layer cannot leak.
TEST(SetupCeiling, TheTargetVoltageModeSetpointIsClampedToTheCeiling) {
  for (double setpoint : {13.99, 14.0, 14.01, 14.8, 14.9}) {
    test::LawRig rig;
    rig.p.SetupCeilingV = 14.0;
    rig.p.TargetVoltageMode = 1;
    rig.p.TargetVoltageSetpoint = setpoint;
    rig.start();
    rig.run(2.0);
    EXPECT_DOUBLE_EQ(rig.law.ChargingVoltageTarget(), std::min(setpoint, 14.0)) << setpoint;
  }
}

TEST(SetupCeiling, CvTuningsHighPhaseStaysUnderTheCeiling) {
  test::LawRig rig;
  rig.p.SetupCeilingV = 14.0;
  rig.p.BulkVoltage = 14.0;  // the lowered set: trip at 14.3, high phase 14.1 before
  rig.p.AbsorptionVoltage = 14.0;
  rig.p.CVTuningMode = 1;
  rig.start();
  double highest = 0.0;
  for (int i = 0; i < 400; ++i) {  // two whole periods of 20 s
    rig.run(0.1);
    highest = std::max(highest, rig.law.ChargingVoltageTarget());
  }
  EXPECT_LE(highest, 14.0);
}

TEST(SetupCeiling, EveryStageAndModeStaysUnderTheCeilingAndNoCeilingChangesNothing) {
  for (int mode = 0; mode < 3; ++mode) {
    test::LawRig rig;
    rig.p.SetupCeilingV = 14.0;
    rig.p.MaintainMode = mode == 1;
    rig.p.BulkVoltage = 14.5;  // a value that leaked past the running layer
    rig.start();
    rig.run(5.0);
    EXPECT_LE(rig.law.ChargingVoltageTarget(), 14.0) << mode;
  }
  test::LawRig set;
  set.p.TargetVoltageMode = 1;
  set.p.TargetVoltageSetpoint = 14.7;  // set up (SetupCeilingV 0): as before
  set.start();
  set.run(1.0);
  EXPECT_DOUBLE_EQ(set.law.ChargingVoltageTarget(), 14.7);
}

TEST(SystemId, MeasuresDeadTimeRiseTimeAndSlopeAndRestores) {
  test::LawRig rig;
  rig.plant.deadTime = 0.05;
  rig.plant.tau = 0.2;
  rig.start();
  rig.run(5.0);
  const double spBefore = rig.law.setpointLimited();
  ASSERT_TRUE(rig.law.startSystemId(rig.now, true));
  EXPECT_TRUE(rig.law.systemIdRunning());
  rig.run(0.5);
  EXPECT_EQ(rig.law.govMode(), GovMode::GOV_BYPASS_SLEW);
  EXPECT_DOUBLE_EQ(rig.duty, rig.p.sysIDBaseDuty);
  rig.run(6.0);
  ASSERT_FALSE(rig.law.systemIdRunning());
  const SystemIdResult& r = rig.law.systemId().result();
  ASSERT_TRUE(r.valid);
  // Dead time 50 ms + 10 % of a 200 ms first-order rise (21 ms).
  EXPECT_NEAR(r.deadTimeMs, 50.0 + 200.0 * std::log(1.0 / 0.9), 10.0);
  EXPECT_NEAR(r.riseTimeMs, 200.0 * std::log(9.0), 15.0);  // 10 -> 90 %: tau ln 9
  EXPECT_NEAR(r.I1 - r.I0, (rig.p.sysIDStepDuty - rig.p.sysIDBaseDuty) * rig.plant.ampsPerPct, 0.5);
  EXPECT_GT(r.slopeAps, 0.0);
  EXPECT_NEAR(rig.law.setpointLimited(), spBefore, 3.0);  // restored (then slewing again)
  EXPECT_EQ(rig.law.currentPID().mode(), Pid::AUTOMATIC);
}

TEST(SystemId, IllegalOutsideAutoAndAbortedByImmediateCut) {
  test::LawRig rig;
  rig.start();
  rig.law.enterSysManual();
  EXPECT_FALSE(rig.law.startSystemId(rig.now, true));
  rig.law.enterSysAuto(rig.sensors(), rig.p);
  EXPECT_FALSE(rig.law.startSystemId(rig.now, false));
  ASSERT_TRUE(rig.law.startSystemId(rig.now, true));
  rig.law.applyImmediateCut();
  EXPECT_FALSE(rig.law.systemIdRunning());
  EXPECT_EQ(rig.law.sysMode(), SysMode::SYS_MODE_FAULT);
  EXPECT_DOUBLE_EQ(rig.law.setpointLimited(), 0.0);
  EXPECT_DOUBLE_EQ(rig.law.lastAppliedDuty(), 0.0);
  EXPECT_EQ(rig.law.currentPID().mode(), Pid::MANUAL);
}

TEST(LimpHome, RampsToThirtyPercentAndLogsEvery30Seconds) {
  Params p;
  ControlLaw law(p);
  EventBatch ev;
  ControlSensors s;
  s.rpm = 2000;
  s.now = fromSec(1);
  law.updateFilters(s, p);
  law.enterSysManual();
  int logs = 0;
  double duty = 0;
  for (int i = 0; i < 40000; ++i) {  // 100 s at 2.5 ms
    s.now += fromUs(2500);
    ev.clear();
    law.updateFilters(s, p);
    duty = law.runLimpHome(s, p, ev);
    for (std::size_t k = 0; k < ev.count; ++k) logs += ev.items[k].code == EventCode::LimpHomeActive;
    if (i == 40) {
      EXPECT_LT(duty, 30.0);  // ramping at DutyRampRate, not a step
    }
  }
  EXPECT_DOUBLE_EQ(duty, 30.0);
  EXPECT_EQ(logs, 4);  // t = 0, 30, 60, 90 s
}

}  // namespace
}  // namespace xr
