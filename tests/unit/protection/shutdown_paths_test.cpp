// The three shutdown paths, the disabled ramp and the cooldown lockout, with
// their timing (ramp slopes, holds, GPIO4 edge, lockout length).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rig.h"

namespace xr::test {
namespace {

using M = FieldControlMode;

TEST(WarningRamp, PhasesSlopesHoldsEdgeAndLockoutLength) {
  Params p;
  p.ShutdownPhase2HoldMs = 400;
  Rig r(p);
  r.warmUp();
  r.tempF = 152.5;  // T1
  r.tick();
  ASSERT_EQ(r.d.mode, M::MODE_WARNING_RAMP_AND_LOCKOUT);
  const TimeNs t0 = r.t - kTick;  // the ramp starts from the duty of the previous tick
  // Phase 1: 50 % -> rpmMinDuty 5 % at 50 %/s = 0.9 s.
  double prev = 50.0;
  TimeNs p2 = -1, p3 = -1, p4 = -1, cut = -1;
  while (r.t - t0 < fromSec(20.0)) {
    if (r.sc.phase == ShutdownPhase::PHASE_1) {
      EXPECT_NEAR(prev - r.sc.dutyPct, r.p.DutyRampRate * toSec(kTick), 1e-9);
      EXPECT_TRUE(r.sc.fieldEnable);
    }
    if (r.sc.phase == ShutdownPhase::PHASE_2) {
      if (p2 < 0) p2 = r.t - t0;
      EXPECT_DOUBLE_EQ(r.sc.dutyPct, 5.0);
    }
    if (r.sc.phase == ShutdownPhase::PHASE_3) {
      if (p3 < 0)
        p3 = r.t - t0;
      else
        EXPECT_NEAR(prev - r.sc.dutyPct, r.p.DutySlowRampRate * toSec(kTick), 1e-9);
    }
    if (r.sc.phase == ShutdownPhase::PHASE_4 && p4 < 0) p4 = r.t - t0;
    if (!r.sc.fieldEnable) {
      cut = r.t - t0;
      break;
    }
    prev = r.sc.dutyPct;
    r.tick();
  }
  EXPECT_NEAR(toSec(p2), 0.9, 0.006);
  EXPECT_NEAR(toSec(p3), 0.9 + 0.4, 0.011);
  EXPECT_NEAR(toSec(p4), 0.9 + 0.4 + 5.0, 0.02);
  EXPECT_NEAR(toSec(cut), 0.9 + 0.4 + 5.0 + 1.0, 0.03);  // SettleTimeBeforeCut after duty reached 0
  EXPECT_EQ(r.sc.dutyPct, 0.0);
  EXPECT_EQ(r.count(EventCode::CutAfterSettle, Reason::REASON_TEMP_WARNING), 1u);
  ASSERT_EQ(r.count(EventCode::LockoutStarted), 1u);
  // The lockout is FIELD_COLLAPSE_DELAY long.
  r.tempF = 100.0;
  const TimeNs back = r.runUntil([&] { return r.d.mode == M::MODE_NORMAL_AUTO_PID; }, fromSec(40.0));
  EXPECT_NEAR(toSec(back), 30.0, 0.011);
}

TEST(WarningRamp, Phase2ZeroSkipsTheHold) {
  Rig r;
  r.warmUp();
  r.tempF = 152.5;
  const TimeNs t0 = r.t;
  const TimeNs p3 = r.runUntil([&] { return r.sc.phase == ShutdownPhase::PHASE_3; }, fromSec(5.0));
  EXPECT_NEAR(toSec(p3), 0.9, 0.011);
  (void)t0;
}

TEST(WarningRamp, DutyBelowRpmMinDutyNeverRampsUp) {
  Rig r;
  r.normalDuty = 3.0;
  r.warmUp();
  r.tempF = 152.5;
  r.tick();
  EXPECT_LE(r.sc.dutyPct, 3.0);
}

// A deviation (docs/deviations.md "Hard over-voltage"): the specification's warning ramp
// with its slew-bypass accelerator is now an immediate cut at the trip, in
// the very tick, with the lockout after it.
TEST(HardOverVoltage, ImmediateCutInTheTickThenLockout) {
  Rig r;
  r.warmUp();
  r.ibv = r.batteryV = 14.81;  // AlternatorHardShutdownV (BulkVoltage 14.5 + 0.3) exceeded
  r.tick();
  EXPECT_EQ(r.d.reason, Reason::REASON_ALT_HARD_SHUTDOWN);
  EXPECT_TRUE(r.sc.applyImmediateCut);
  EXPECT_FALSE(r.sc.fieldEnable);
  EXPECT_EQ(r.sc.dutyPct, 0.0);
  EXPECT_TRUE(r.sup.flags().lockoutActive);
  r.ibv = r.batteryV = 13.5;
  r.tick();
  EXPECT_EQ(r.d.mode, M::MODE_LOCKOUT_RAMP);
  EXPECT_FALSE(r.sc.fieldEnable);
}

TEST(HardOverVoltage, JustUnderTheTripNothingHappens) {
  Rig r;
  r.warmUp();
  r.ibv = r.batteryV = 14.79;
  r.run(fromSec(2.0));
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_AUTO_PID);
  EXPECT_TRUE(r.sc.fieldEnable);
}

TEST(HardOverVoltage, CutsInManualWithoutLockingManualOut) {
  Rig r;
  r.manual = true;
  r.warmUp();
  r.ibv = r.batteryV = 14.81;
  r.tick();
  EXPECT_EQ(r.d.reason, Reason::REASON_ALT_HARD_SHUTDOWN);
  EXPECT_FALSE(r.sc.fieldEnable);
  r.ibv = r.batteryV = 13.5;  // MANUAL bypasses the lockout: the operator's duty resumes
  r.tick();
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_MANUAL);
}

TEST(CriticalRamp, PhaseFourDirectThenCutAfterSettleThenLockout) {
  Rig r;
  r.warmUp();
  r.freezeCh1 = true;  // current stale
  ASSERT_GE(r.runUntil([&] { return r.d.mode == M::MODE_CRITICAL_RAMP; }, fromSec(1.0)), 0);
  EXPECT_EQ(r.sc.dutyPct, 0.0);
  EXPECT_TRUE(r.sc.fieldEnable);
  const TimeNs cut = r.runUntil([&] { return !r.sc.fieldEnable; }, fromSec(3.0));
  EXPECT_NEAR(toSec(cut), 1.0, 0.006);  // SettleTimeBeforeCut
  EXPECT_EQ(r.count(EventCode::LockoutStarted), 1u);
}

TEST(ImmediateCut, NoDuplicateLoggingWhileAlreadyCut) {
  Rig r;
  r.warmUp();
  r.tempF = 161.0;  // T3
  r.run(fromSec(2.0));
  EXPECT_EQ(r.count(EventCode::ImmediateCut, Reason::REASON_TEMP_CRITICAL), 1u);
  r.altAmps = 80.0;  // hard OC on top: higher priority, field already cut
  r.run(fromSec(1.0));
  EXPECT_EQ(r.d.reason, Reason::REASON_HARD_OVERCURRENT);
  EXPECT_EQ(r.count(EventCode::ImmediateCut), 1u);
  EXPECT_TRUE(r.sc.applyImmediateCut);  // the resets still run every tick
}

TEST(CoFiring, HardwareAlertAndSoftwareHardShutdownLogOnce) {
  Rig r;
  r.warmUp();
  // Same event: raw IBV above AlternatorHardShutdownV and the chip's averaged alert.
  r.ibv = r.batteryV = 14.9;
  r.inaAlert = true;
  r.run(fromSec(2.0));
  EXPECT_EQ(r.d.reason, Reason::REASON_INA_OVERVOLTAGE);
  EXPECT_FALSE(r.sc.fieldEnable);
  const std::size_t lines = r.count(EventCode::InaLatchSet) + r.count(EventCode::ImmediateCut) +
                            r.count(EventCode::CutAfterSettle) +
                            r.count(EventCode::ProtectionTrip, Reason::REASON_ALT_HARD_SHUTDOWN);
  EXPECT_EQ(lines, 1u);
  EXPECT_EQ(r.count(EventCode::InaLatchSet), 1u);
}

TEST(T2Sustained, StaysOffUntilReenabled) {
  Rig r;
  r.warmUp();
  r.tempF = 153.0;  // T1 held
  const TimeNs t2 = r.runUntil([&] { return r.sup.flags().tempSustained; }, fromSec(130.0), fromMs(10));
  EXPECT_NEAR(toSec(t2), r.p.TempSustainedTimeout, 0.02);
  r.tempF = 100.0;  // cools down: no auto-restart
  r.run(fromSec(120.0), fromMs(10));
  EXPECT_EQ(r.d.reason, Reason::REASON_TEMP_SUSTAINED);
  EXPECT_FALSE(r.sc.fieldEnable);
  r.sup.reenableField();
  r.tick();
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_AUTO_PID);
  EXPECT_TRUE(r.sc.fieldEnable);
}

TEST(T2Sustained, TimerResetsWhenTemperatureDropsBelowWarning) {
  Rig r;
  r.warmUp();
  r.tempF = 153.0;
  r.run(fromSec(100.0), fromMs(10));
  r.tempF = 151.0;
  r.tick(fromMs(10));
  r.tempF = 153.0;
  r.run(fromSec(100.0), fromMs(10));
  EXPECT_FALSE(r.sup.flags().tempSustained);
}

TEST(Lockout, ReArmsWhenTheFaultPersists) {
  Rig r;
  r.warmUp();
  r.tempF = 152.5;
  ASSERT_GE(r.runUntil([&] { return r.sup.flags().lockoutActive; }, fromSec(10.0)), 0);
  const TimeNs rearm = r.runUntil([&] { return r.count(EventCode::LockoutStarted) == 2; }, fromSec(35.0));
  EXPECT_NEAR(toSec(rearm), 30.0, 0.011);
  EXPECT_EQ(r.count(EventCode::LockoutExpired), 1u);
  EXPECT_FALSE(r.sc.fieldEnable);  // never re-energised in between
}

TEST(Lockout, HoldsEvenWhenTheFaultClearsAndNotAfterImmediateCut) {
  Rig r;
  r.warmUp();
  r.ibv = r.batteryV = 14.9;
  ASSERT_GE(r.runUntil([&] { return r.sup.flags().lockoutActive; }, fromSec(10.0)), 0);
  r.ibv = r.batteryV = 13.5;
  r.run(fromSec(29.0));
  EXPECT_EQ(r.d.mode, M::MODE_LOCKOUT_RAMP);
  EXPECT_FALSE(r.sc.fieldEnable);
}

TEST(Lockout, FaultClearingMidRampStillCompletesTheRamp) {
  Rig r;
  r.warmUp();
  r.tempF = 152.5;  // T1
  r.tick();
  ASSERT_EQ(r.d.mode, M::MODE_WARNING_RAMP_AND_LOCKOUT);
  r.tempF = 140.0;  // the trip clears as the duty falls
  r.run(fromSec(0.5));
  EXPECT_EQ(r.d.mode, M::MODE_WARNING_RAMP_AND_LOCKOUT);
  EXPECT_EQ(r.d.reason, Reason::REASON_TEMP_WARNING);
  ASSERT_GE(r.runUntil([&] { return r.sup.flags().lockoutActive; }, fromSec(10.0)), 0);
}

TEST(DisabledRamp, OnOffRampsDownWithoutAlarmOrLockout) {
  Rig r;
  r.warmUp();
  r.OnOffOrder = false;
  r.tick();
  EXPECT_EQ(r.d.mode, M::MODE_DISABLED_RAMP);
  EXPECT_EQ(r.d.reason, Reason::REASON_ONOFF_DISABLED);
  EXPECT_EQ(r.sc.phase, ShutdownPhase::PHASE_1);
  EXPECT_FALSE(r.sc.faultAlarm);
  ASSERT_GE(r.runUntil([&] { return !r.sc.fieldEnable; }, fromSec(10.0)), 0);
  r.run(fromSec(1.0));
  EXPECT_FALSE(r.buzzer);
  EXPECT_EQ(r.count(EventCode::LockoutStarted), 0u);
  r.OnOffOrder = true;
  r.tick();
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_AUTO_PID);
}

TEST(DisabledRamp, WarningDuringDisabledRampBringsLockout) {
  Rig r;
  r.warmUp();
  r.ignition = false;
  r.run(fromSec(0.2));
  r.tempF = 152.5;
  ASSERT_GE(r.runUntil([&] { return !r.sc.fieldEnable; }, fromSec(10.0)), 0);
  EXPECT_EQ(r.count(EventCode::LockoutStarted), 1u);
}

TEST(FaultAlarm, WarningRampSoundsTheBuzzer) {
  Rig r;
  r.warmUp();
  r.tempF = 152.5;
  r.run(fromMs(300));
  EXPECT_TRUE(r.sc.faultAlarm);
  EXPECT_TRUE(r.buzzer);
}

TEST(ModeEvents, SequencerLeavesModeChangedToTheCaller) {
  Rig r;
  r.warmUp();
  r.tempF = 161.0;
  r.tick();
  r.tempF = 100.0;
  r.tick();
  EXPECT_EQ(r.count(EventCode::ModeChanged), 0u);  // Regulator::step logs it once
  EXPECT_EQ(r.count(EventCode::ImmediateCut, Reason::REASON_TEMP_CRITICAL), 1u);
}

}  // namespace
}  // namespace xr::test
