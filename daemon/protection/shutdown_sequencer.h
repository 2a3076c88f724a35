#pragma once
// ShutdownSequencer: the three shutdown paths of docs/protections.md
// ("Three shutdown paths", "Cooldown lockout") plus MODE_DISABLED_RAMP.
// Called every tick with the tick's mode decision; it owns GPIO4's cut, the
// ramp's phase and duty, the ramp latch and the cooldown lockout.
//
//   immediate cut  -> duty 0 and GPIO4 LOW this tick, phase jumps to PHASE_4,
//                     no cooldown (INA OV, hard OC, T3, RPM gate, bank size);
//                     the alternator hard shutdown (an immediate cut here,
//                     a warning ramp in the specification) keeps its lockout
//   warning ramp   -> P1 slew to rpmMinDuty at DutyRampRate, P2 hold
//                     ShutdownPhase2HoldMs, P3 slew to 0 at DutySlowRampRate,
//                     P4 hold SettleTimeBeforeCut then GPIO4 LOW, then the
//                     FIELD_COLLAPSE_DELAY lockout (T2: no lockout, no restart)
//   critical ramp  -> straight to P4 (duty 0 at once, slew off), then lockout
//   disabled ramp  -> the warning ramp's shape, no alarm, no lockout
#include "core/modes.h"
#include "core/time.h"
#include "params/params.h"
#include "protection/mode_selection.h"
#include "protection/protection_log.h"
#include "protection/tick_snapshot.h"

namespace xr {

// What the sequencer commands this tick.
struct ShutdownCommand {
  bool active = false;      // a non-normal mode owns the outputs this tick
  double dutyPct = 0.0;     // duty to apply (already slewed; 0..100)
  bool fieldEnable = true;  // GPIO4; false once cut
  GovMode govMode = GovMode::GOV_NORMAL_SLEW;
  double effectiveMin = 0.0;       // always 0 during shutdown (docs/control.md)
  bool applyImmediateCut = false;  // control must run its applyImmediateCut() resets
  ShutdownPhase phase = ShutdownPhase::PHASE_NONE;
  bool faultAlarm = false;  // critical/warning/lockout (not DISABLED): GPIO21 wants ON
};

struct ShutdownInput {
  ModeDecision d;                // this tick's mode and reason
  double lastAppliedDuty = 0.0;  // the duty applied on the last tick (a ramp starts from it)
  double rpmMinDuty = 0.0;       // phase 1's floor
  TimeNs prevNow = 0;            // the previous tick's time (the ramp step's dt)
};

class ShutdownSequencer {
 public:
  // log: stamped with in.d.mode (the mode this decision selects).
  ShutdownCommand update(const ShutdownInput& in, const Params& p, const ProtectionLog& log) noexcept;
  // Cooldown lockout expiry ("After it elapses the system retries"), from
  // the detectors' step.
  void expireLockout(const ProtectionLog& log) noexcept;
  // reenable_field: a ramp latched for reason r is released.
  void releaseLatch(Reason r) noexcept;
  // The ramp latch and the lockout, as mode selection reads them.
  void publish(ProtectionFlags& f) const noexcept;

  FieldControlMode mode() const noexcept { return mode_; }
  ShutdownPhase phase() const noexcept { return phase_; }
  bool fieldCut() const noexcept { return fieldCut_; }
  bool faultAlarm() const noexcept { return faultAlarm_; }
  bool lockoutActive() const noexcept { return lockoutActive_; }
  double lockoutRemainingS(TimeNs now) const noexcept;

 private:
  void startLockout(const Params& p, const ProtectionLog& log) noexcept;
  void cutImmediately(Reason reason, double lastAppliedDuty, const Params& p,
                      const ProtectionLog& log) noexcept;
  void latchRamp(const ModeDecision& d, bool faultRamp) noexcept;
  GovMode startRamp(FieldControlMode mode, double lastAppliedDuty, TimeNs now) noexcept;
  void stepRampPhases(const ShutdownInput& in, bool faultRamp, const Params& p,
                      const ProtectionLog& log) noexcept;

  FieldControlMode mode_ = FieldControlMode::MODE_DISABLED_RAMP;  // the last decision's mode
  Reason reason_ = Reason::NONE;                                  // and its reason
  ShutdownPhase phase_ = ShutdownPhase::PHASE_NONE;               // the ramp's phase
  TimeNs phaseStart_ = 0;                                         // when that phase began
  double duty_ = 0.0;                                             // the ramp's duty now
  bool fieldCut_ = true;                                          // GPIO4 LOW (it starts LOW at boot)
  bool faultAlarm_ = false;                                       // a fault mode wants the buzzer
  bool rampLatched_ = false;  // a warning/critical ramp runs to its cut even if its trigger clears
  FieldControlMode rampMode_ = FieldControlMode::MODE_WARNING_RAMP_AND_LOCKOUT;  // the latched ramp
  Reason rampReason_ = Reason::NONE;                                             // and its reason
  bool lockoutActive_ = false;                                                   // the cooldown lockout holds
  TimeNs lockoutUntil_ = 0;                                                      // its end
};

}  // namespace xr
