// ShutdownSequencer on its own: an immediate cut the same tick, the warning
// ramp's phases and its lockout, the critical ramp straight to the settle,
// the lockout's expiry, and the latch reenable_field releases.
#include "protection/shutdown_sequencer.h"

#include <gtest/gtest.h>

#include "part_log.h"

namespace xr::test {
namespace {

using M = FieldControlMode;

struct SeqRig {
  Params p;
  ShutdownSequencer seq;
  PartLog log;
  TimeNs prev = log.t;
  double duty = 50.0;
  ShutdownCommand tick(M mode, Reason reason, TimeNs dt = fromMs(5)) {
    prev = log.t;
    log.t += dt;
    log.mode = mode;
    const ShutdownCommand c = seq.update({{mode, reason}, duty, 5.0, prev}, p, log.at());
    if (c.active) duty = c.dutyPct;
    log.collect();
    return c;
  }
};

TEST(ShutdownSequencerPart, ImmediateCutDropsTheFieldTheSameTick) {
  SeqRig r;
  r.tick(M::MODE_NORMAL_AUTO_PID, Reason::NONE);
  const ShutdownCommand c = r.tick(M::MODE_CRITICAL_RAMP, Reason::REASON_HARD_OVERCURRENT);
  EXPECT_TRUE(c.applyImmediateCut);
  EXPECT_FALSE(c.fieldEnable);
  EXPECT_DOUBLE_EQ(c.dutyPct, 0.0);
  EXPECT_FALSE(r.seq.lockoutActive());  // no cooldown for the immediate cuts
  EXPECT_EQ(r.log.count(EventCode::ImmediateCut, Reason::REASON_HARD_OVERCURRENT), 1u);
}

TEST(ShutdownSequencerPart, WarningRampRunsItsPhasesThenCutsAndLocksOut) {
  SeqRig r;
  r.tick(M::MODE_NORMAL_AUTO_PID, Reason::NONE);
  ShutdownCommand c = r.tick(M::MODE_WARNING_RAMP_AND_LOCKOUT, Reason::REASON_TEMP_WARNING);
  EXPECT_EQ(c.phase, ShutdownPhase::PHASE_1);
  EXPECT_TRUE(c.fieldEnable);
  EXPECT_LT(c.dutyPct, 50.0);
  // The trigger clears: the latched ramp still runs to its cut.
  for (int i = 0; i < 2000 && r.seq.phase() != ShutdownPhase::PHASE_DONE; ++i)
    c = r.tick(M::MODE_WARNING_RAMP_AND_LOCKOUT, Reason::REASON_TEMP_WARNING, fromMs(10));
  EXPECT_FALSE(c.fieldEnable);
  EXPECT_TRUE(r.seq.lockoutActive());
  EXPECT_EQ(r.log.count(EventCode::CutAfterSettle), 1u);
  EXPECT_EQ(r.log.count(EventCode::LockoutStarted), 1u);
  // The lockout ends after FIELD_COLLAPSE_DELAY, not before.
  r.log.t += fromMs(r.p.FIELD_COLLAPSE_DELAY) - fromMs(10);
  r.seq.expireLockout(r.log.at());
  EXPECT_TRUE(r.seq.lockoutActive());
  r.log.t += fromMs(10);
  r.seq.expireLockout(r.log.at());
  EXPECT_FALSE(r.seq.lockoutActive());
}

TEST(ShutdownSequencerPart, CriticalRampSkipsToTheSettleAndCutsAfterIt) {
  SeqRig r;
  r.tick(M::MODE_NORMAL_AUTO_PID, Reason::NONE);
  ShutdownCommand c = r.tick(M::MODE_CRITICAL_RAMP, Reason::REASON_CURRENT_STALE);
  EXPECT_EQ(c.phase, ShutdownPhase::PHASE_4);
  EXPECT_DOUBLE_EQ(c.dutyPct, 0.0);
  EXPECT_TRUE(c.fieldEnable);
  EXPECT_EQ(c.govMode, GovMode::GOV_BYPASS_SLEW);
  c = r.tick(M::MODE_CRITICAL_RAMP, Reason::REASON_CURRENT_STALE,
             fromMs(r.p.SettleTimeBeforeCut) - fromMs(10));
  EXPECT_TRUE(c.fieldEnable);  // just before the settle ends
  c = r.tick(M::MODE_CRITICAL_RAMP, Reason::REASON_CURRENT_STALE, fromMs(10));
  EXPECT_FALSE(c.fieldEnable);
  EXPECT_TRUE(r.seq.lockoutActive());
}

TEST(ShutdownSequencerPart, SustainedTemperatureLatchIsReleasedByReenable) {
  SeqRig r;
  r.tick(M::MODE_NORMAL_AUTO_PID, Reason::NONE);
  r.tick(M::MODE_WARNING_RAMP_AND_LOCKOUT, Reason::REASON_TEMP_SUSTAINED);
  ProtectionFlags f;
  r.seq.publish(f);
  EXPECT_TRUE(f.rampLatched);
  r.seq.releaseLatch(Reason::REASON_TEMP_WARNING);  // another reason: kept
  r.seq.publish(f);
  EXPECT_TRUE(f.rampLatched);
  r.seq.releaseLatch(Reason::REASON_TEMP_SUSTAINED);
  r.seq.publish(f);
  EXPECT_FALSE(f.rampLatched);
}

TEST(ShutdownSequencerPart, DisabledRampHasNoAlarmAndNoLockout) {
  SeqRig r;
  r.tick(M::MODE_NORMAL_AUTO_PID, Reason::NONE);
  ShutdownCommand c;
  for (int i = 0; i < 20000 && r.seq.phase() != ShutdownPhase::PHASE_DONE; ++i) {
    c = r.tick(M::MODE_DISABLED_RAMP, Reason::REASON_IGNITION_OFF, fromMs(10));
    EXPECT_FALSE(c.faultAlarm);
  }
  EXPECT_FALSE(c.fieldEnable);
  EXPECT_FALSE(r.seq.lockoutActive());
}

}  // namespace
}  // namespace xr::test
