// ShutdownSequencer: the immediate cut, the ramps' phases and the lockout.
#include "protection/shutdown_sequencer.h"

#include <algorithm>
#include <cmath>

#include "params/constants.h"
#include "params/derived.h"

namespace xr {
namespace {
using M = FieldControlMode;
}

void ShutdownSequencer::startLockout(const Params& p, const ProtectionLog& log) noexcept {
  lockoutUntil_ = log.now() + fromMs(p.FIELD_COLLAPSE_DELAY);
  lockoutActive_ = true;
  rampLatched_ = false;
  log.push(EventCode::LockoutStarted, EventLevel::Warning, reason_, p.FIELD_COLLAPSE_DELAY / 1000.0);
}

void ShutdownSequencer::expireLockout(const ProtectionLog& log) noexcept {
  if (!lockoutActive_ || log.now() < lockoutUntil_) return;
  lockoutActive_ = false;
  log.push(EventCode::LockoutExpired, EventLevel::Info, Reason::REASON_LOCKOUT);
}

double ShutdownSequencer::lockoutRemainingS(TimeNs now) const noexcept {
  return lockoutActive_ ? std::max(0.0, toSec(lockoutUntil_ - now)) : 0.0;
}

void ShutdownSequencer::releaseLatch(Reason r) noexcept {
  if (rampLatched_ && rampReason_ == r) rampLatched_ = false;
}

void ShutdownSequencer::publish(ProtectionFlags& f) const noexcept {
  f.rampLatched = rampLatched_;
  f.rampLatchedMode = rampMode_;
  f.rampLatchedReason = rampReason_;
  f.lockoutActive = lockoutActive_;
}

ShutdownCommand ShutdownSequencer::update(const ShutdownInput& in, const Params& p,
                                          const ProtectionLog& log) noexcept {
  // ModeChanged ("Entering normal mode" / "Exiting normal mode: <reason>") is
  // emitted by Regulator::step with its enterSys* transition, not here, so
  // the journal gets one line per transition.
  const ModeDecision& d = in.d;
  mode_ = d.mode;
  reason_ = d.reason;

  ShutdownCommand c;
  if (isNormalMode(d.mode)) {
    phase_ = ShutdownPhase::PHASE_NONE;
    fieldCut_ = false;
    rampLatched_ = false;
    faultAlarm_ = false;
    duty_ = in.lastAppliedDuty;
    c.active = false;
    c.fieldEnable = true;
    c.dutyPct = in.lastAppliedDuty;
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
    cutImmediately(d.reason, in.lastAppliedDuty, p, log);
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
      if (faultRamp && d.reason != Reason::REASON_TEMP_SUSTAINED) startLockout(p, log);
    } else {
      c.govMode = startRamp(d.mode, in.lastAppliedDuty, log.now());
      stepRampPhases(in, faultRamp, p, log);
    }
  }
  c.dutyPct = duty_;
  c.fieldEnable = !fieldCut_;
  c.phase = phase_;
  return c;
}

// The immediate-cut reasons: GPIO4 LOW this tick, no ramp.
void ShutdownSequencer::cutImmediately(Reason reason, double lastAppliedDuty, const Params& p,
                                       const ProtectionLog& log) noexcept {
  // Duplicate logging suppressed when already cut; the INA228 alert has
  // already pulled GPIO4 LOW in hardware, its InaLatchSet line is the log.
  if (!fieldCut_ && reason != Reason::REASON_INA_OVERVOLTAGE)
    log.push(EventCode::ImmediateCut,
             reason == Reason::REASON_RPM_LOW ? EventLevel::Info : EventLevel::Critical, reason,
             lastAppliedDuty);
  // The hard over-voltage cut keeps the specification's cooldown lockout.
  if (!fieldCut_ && reason == Reason::REASON_ALT_HARD_SHUTDOWN) startLockout(p, log);
  fieldCut_ = true;
  duty_ = 0.0;
  phase_ = ShutdownPhase::PHASE_4;  // a later re-entry never re-runs the ramp
}

// A warning/critical ramp runs to its cut even if its trigger clears.
void ShutdownSequencer::latchRamp(const ModeDecision& d, bool faultRamp) noexcept {
  if (faultRamp && !fieldCut_ && !rampLatched_) {
    rampLatched_ = true;
    rampMode_ = d.mode;
    rampReason_ = d.reason;
  } else if (faultRamp && rampLatched_ && d.mode == M::MODE_CRITICAL_RAMP) {
    rampMode_ = d.mode;  // escalation: a warning ramp became critical
    rampReason_ = d.reason;
  }
}

// Ramp phases (GPIO4 still HIGH): the first tick of a ramp starts phase 1
// from the applied duty; a critical ramp goes straight to phase 4 with the
// slew limiter off. Returns the governor mode of the ramp.
GovMode ShutdownSequencer::startRamp(FieldControlMode mode, double lastAppliedDuty, TimeNs now) noexcept {
  if (phase_ == ShutdownPhase::PHASE_NONE || phase_ == ShutdownPhase::PHASE_DONE) {
    phase_ = ShutdownPhase::PHASE_1;
    phaseStart_ = now;
    duty_ = std::max(0.0, lastAppliedDuty);
  }
  const bool critical = mode == M::MODE_CRITICAL_RAMP;
  if (critical && phase_ != ShutdownPhase::PHASE_4) {
    phase_ = ShutdownPhase::PHASE_4;  // skip phases 1-3, slew limiter off
    phaseStart_ = now;
  }
  return critical ? GovMode::GOV_BYPASS_SLEW : GovMode::GOV_NORMAL_SLEW;
}

// Phases 1-4 (docs/protections.md "Shutdown paths"): down to the RPM floor at
// DutyRampRate, a hold, down to 0 at DutySlowRampRate, the settle, then the
// cut. At most one ramp step per tick; a phase that ends passes on at once.
void ShutdownSequencer::stepRampPhases(const ShutdownInput& in, bool faultRamp, const Params& p,
                                       const ProtectionLog& log) noexcept {
  const TimeNs now = log.now();
  // The step's dt, computed only on the ticks that ramp.
  auto dtSec = [&] { return std::clamp(toSec(now - in.prevNow), 0.0, 1.0); };
  const double floorDuty = std::max(0.0, in.rpmMinDuty);
  bool rampedThisTick = false;
  if (phase_ == ShutdownPhase::PHASE_1) {
    if (duty_ > floorDuty) {
      duty_ = std::max(floorDuty, duty_ - p.DutyRampRate * dtSec());
      rampedThisTick = true;
    }
    if (duty_ > floorDuty) return;
    phase_ = ShutdownPhase::PHASE_2;
    phaseStart_ = now;
  }
  if (phase_ == ShutdownPhase::PHASE_2) {
    if (now - phaseStart_ < fromMs(p.ShutdownPhase2HoldMs)) return;
    phase_ = ShutdownPhase::PHASE_3;
    phaseStart_ = now;
  }
  if (phase_ == ShutdownPhase::PHASE_3) {
    if (duty_ > 0.0) {
      if (rampedThisTick) return;
      duty_ = std::max(0.0, duty_ - p.DutySlowRampRate * dtSec());
    }
    if (duty_ > 0.0) return;
    phase_ = ShutdownPhase::PHASE_4;
    phaseStart_ = now;
  }
  if (phase_ == ShutdownPhase::PHASE_4) {
    duty_ = 0.0;
    if (now - phaseStart_ >= fromMs(p.SettleTimeBeforeCut)) {
      fieldCut_ = true;
      phase_ = ShutdownPhase::PHASE_DONE;
      log.push(EventCode::CutAfterSettle, faultRamp ? EventLevel::Warning : EventLevel::Info, in.d.reason);
      if (faultRamp && in.d.reason != Reason::REASON_TEMP_SUSTAINED) startLockout(p, log);
    }
  }
}

}  // namespace xr
