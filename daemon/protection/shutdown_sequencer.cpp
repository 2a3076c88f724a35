// runShutdownPath(): the three shutdown paths of docs/protections.md
// ("Three shutdown paths", "Cooldown lockout") plus MODE_DISABLED_RAMP.
//
//   immediate cut  -> duty 0 and GPIO4 LOW this tick, phase jumps to PHASE_4,
//                     no cooldown (INA OV, hard OC, T3, RPM gate); the
//                     alternator hard shutdown (ours: an immediate cut) keeps
//                     its lockout
//   warning ramp   -> P1 slew to rpmMinDuty at DutyRampRate, P2 hold
//                     ShutdownPhase2HoldMs, P3 slew to 0 at DutySlowRampRate,
//                     P4 hold SettleTimeBeforeCut then GPIO4 LOW, then the
//                     FIELD_COLLAPSE_DELAY lockout (T2: no lockout, no restart)
//   critical ramp  -> straight to P4 (duty 0 at once, slew off), then lockout
//   disabled ramp  -> the warning ramp's shape, no alarm, no lockout
#include <algorithm>
#include <cmath>

#include "params/constants.h"
#include "params/derived.h"
#include "protection/protection_supervisor.h"

namespace xr {
namespace {
using M = FieldControlMode;
}

void ProtectionSupervisor::startLockout(EventBatch& ev) noexcept {
  lockoutUntil_ = now_ + fromMs(p_.FIELD_COLLAPSE_DELAY);
  flags_.lockoutActive = true;
  flags_.rampLatched = false;
  push(ev, EventCode::LockoutStarted, EventLevel::Warning, lastReason_, p_.FIELD_COLLAPSE_DELAY / 1000.0);
}

ShutdownCommand ProtectionSupervisor::runShutdownPath(const ModeDecision& d, double lastAppliedDuty,
                                                      double rpmMinDuty, EventBatch& ev) noexcept {
  // ModeChanged ("Entering normal mode" / "Exiting normal mode: <reason>") is
  // emitted by Regulator::step with its enterSys* transition, not here, so
  // the journal gets one line per transition.
  lastMode_ = d.mode;
  lastReason_ = d.reason;
  firstSequencerTick_ = false;

  ShutdownCommand c;
  if (isNormalMode(d.mode)) {
    phase_ = ShutdownPhase::PHASE_NONE;
    fieldCut_ = false;
    flags_.rampLatched = false;
    faultAlarm_ = false;
    duty_ = lastAppliedDuty;
    c.active = false;
    c.fieldEnable = true;
    c.dutyPct = lastAppliedDuty;
    c.phase = phase_;
    return c;
  }

  c.active = true;
  c.effectiveMin = 0.0;
  const bool lockoutHold = d.mode == M::MODE_LOCKOUT_RAMP && d.reason == Reason::REASON_LOCKOUT;
  const bool faultRamp = d.mode == M::MODE_CRITICAL_RAMP || d.mode == M::MODE_WARNING_RAMP_AND_LOCKOUT;
  // The buzzer (GPIO21) in non-normal modes except DISABLED (docs/protections.md,
  // the buzzer row's "fault mode"); an auto-zero measurement is not a fault either.
  faultAlarm_ = faultRamp || lockoutHold;
  c.faultAlarm = faultAlarm_;

  if (isImmediateCutReason(d.reason)) {
    cutImmediately(d.reason, lastAppliedDuty, ev);
    c.applyImmediateCut = true;
    c.govMode = GovMode::GOV_BYPASS_SLEW;
  } else if (lockoutHold && fieldCut_) {
    duty_ = 0.0;
    phase_ = ShutdownPhase::PHASE_DONE;
  } else {
    latchRamp(d, faultRamp);
    if (fieldCut_) {
      // Field already off: nothing to ramp. The fault persists (e.g. after
      // the lockout expired): a new lockout.
      duty_ = 0.0;
      phase_ = ShutdownPhase::PHASE_DONE;
      if (faultRamp && d.reason != Reason::REASON_TEMP_SUSTAINED) startLockout(ev);
    } else {
      c.govMode = startRamp(d.mode, lastAppliedDuty);
      stepRampPhases(std::max(0.0, rpmMinDuty), faultRamp, d.reason, ev);
    }
  }
  c.dutyPct = duty_;
  c.fieldEnable = !fieldCut_;
  c.phase = phase_;
  return c;
}

// The immediate-cut reasons: GPIO4 LOW this tick, no ramp.
void ProtectionSupervisor::cutImmediately(Reason reason, double lastAppliedDuty, EventBatch& ev) noexcept {
  // Duplicate logging suppressed when already cut; the INA228 alert has
  // already pulled GPIO4 LOW in hardware, its InaLatchSet line is the log.
  if (!fieldCut_ && reason != Reason::REASON_INA_OVERVOLTAGE)
    push(ev, EventCode::ImmediateCut,
         reason == Reason::REASON_RPM_LOW ? EventLevel::Info : EventLevel::Critical, reason, lastAppliedDuty);
  // The hard over-voltage cut keeps the seed's cooldown lockout.
  if (!fieldCut_ && reason == Reason::REASON_ALT_HARD_SHUTDOWN) startLockout(ev);
  fieldCut_ = true;
  duty_ = 0.0;
  phase_ = ShutdownPhase::PHASE_4;  // a later re-entry never re-runs the ramp
}

// A warning/critical ramp runs to its cut even if its trigger clears.
void ProtectionSupervisor::latchRamp(const ModeDecision& d, bool faultRamp) noexcept {
  if (faultRamp && !fieldCut_ && !flags_.rampLatched) {
    flags_.rampLatched = true;
    flags_.rampLatchedMode = d.mode;
    flags_.rampLatchedReason = d.reason;
  } else if (faultRamp && flags_.rampLatched && d.mode == M::MODE_CRITICAL_RAMP) {
    flags_.rampLatchedMode = d.mode;  // escalation: a warning ramp became critical
    flags_.rampLatchedReason = d.reason;
  }
}

// Ramp phases (GPIO4 still HIGH): the first tick of a ramp starts phase 1
// from the applied duty; a critical ramp goes straight to phase 4 with the
// slew limiter off. Returns the governor mode of the ramp.
GovMode ProtectionSupervisor::startRamp(FieldControlMode mode, double lastAppliedDuty) noexcept {
  if (phase_ == ShutdownPhase::PHASE_NONE || phase_ == ShutdownPhase::PHASE_DONE) {
    phase_ = ShutdownPhase::PHASE_1;
    phaseStart_ = now_;
    duty_ = std::max(0.0, lastAppliedDuty);
  }
  const bool critical = mode == M::MODE_CRITICAL_RAMP;
  if (critical && phase_ != ShutdownPhase::PHASE_4) {
    phase_ = ShutdownPhase::PHASE_4;  // skip phases 1-3, slew limiter off
    phaseStart_ = now_;
  }
  // (The seed's slew-bypass accelerator for the hard-shutdown warning ramp is
  // gone with that ramp: the hard shutdown is an immediate cut.)
  return critical ? GovMode::GOV_BYPASS_SLEW : GovMode::GOV_NORMAL_SLEW;
}

// Phases 1-4 (docs/protections.md "Shutdown paths"): down to the RPM floor at
// DutyRampRate, a hold, down to 0 at DutySlowRampRate, the settle, then the
// cut. At most one ramp step per tick; a phase that ends passes on at once.
void ProtectionSupervisor::stepRampPhases(double floorDuty, bool faultRamp, Reason reason,
                                          EventBatch& ev) noexcept {
  bool rampedThisTick = false;
  if (phase_ == ShutdownPhase::PHASE_1) {
    if (duty_ > floorDuty) {
      duty_ = std::max(floorDuty, duty_ - p_.DutyRampRate * dtSec());
      rampedThisTick = true;
    }
    if (duty_ > floorDuty) return;
    phase_ = ShutdownPhase::PHASE_2;
    phaseStart_ = now_;
  }
  if (phase_ == ShutdownPhase::PHASE_2) {
    if (now_ - phaseStart_ < fromMs(p_.ShutdownPhase2HoldMs)) return;
    phase_ = ShutdownPhase::PHASE_3;
    phaseStart_ = now_;
  }
  if (phase_ == ShutdownPhase::PHASE_3) {
    if (duty_ > 0.0) {
      if (rampedThisTick) return;
      duty_ = std::max(0.0, duty_ - p_.DutySlowRampRate * dtSec());
    }
    if (duty_ > 0.0) return;
    phase_ = ShutdownPhase::PHASE_4;
    phaseStart_ = now_;
  }
  if (phase_ == ShutdownPhase::PHASE_4) {
    duty_ = 0.0;
    if (now_ - phaseStart_ >= fromMs(p_.SettleTimeBeforeCut)) {
      fieldCut_ = true;
      phase_ = ShutdownPhase::PHASE_DONE;
      push(ev, EventCode::CutAfterSettle, faultRamp ? EventLevel::Warning : EventLevel::Info, reason);
      if (faultRamp && reason != Reason::REASON_TEMP_SUSTAINED) startLockout(ev);
    }
  }
}

}  // namespace xr
