#pragma once
// selectFieldControlMode() / selectFieldEventReason(): the pure priority
// functions of docs/protections.md "Mode priority" as amended by
// docs/protections.md "Protections".
//
// Priority, highest first (first match wins):
//   0. INA228 software latch -> MODE_CRITICAL_RAMP, REASON_INA_OVERVOLTAGE
//      (immediate cut). Every mode, Limp Home included ("pre-gate").
//   L. Limp Home -> MODE_LIMP_HOME. Bypasses every protection below. Only the
//      explicit "do not charge" inputs (ignition off, OnOff = 0, BMS) still
//      give MODE_DISABLED_RAMP: they are not protections but orders (see
//      docs/protections.md for why). The battery temperature limits
//      (REASON_BATTERY_COLD / _HOT) are such orders too.
//   1. Hard overcurrent, then T3 -> MODE_CRITICAL_RAMP (immediate cut).
//      AUTO and MANUAL.
//   1b. RPM gate -> MODE_DISABLED_RAMP, REASON_RPM_LOW (immediate cut, no
//      alarm: a stopped engine is not a fault). AUTO and MANUAL.
//   2. MANUAL -> MODE_DISABLED_RAMP when charging is disabled, else
//      MODE_NORMAL_MANUAL. Everything below is AUTO only.
//   3. Cooldown lockout -> MODE_LOCKOUT_RAMP, REASON_LOCKOUT.
//   4. Critical ramp: disagreement critical, implausible, T5 stale, current
//      stale (or a latched critical ramp still running) -> MODE_CRITICAL_RAMP.
//   5. Warning ramp: alternator hard shutdown, T2, T1, disagreement warning
//      (or a latched warning ramp still running) -> MODE_WARNING_RAMP_AND_LOCKOUT.
//   6. Auto-zero measurement -> MODE_LOCKOUT_RAMP, REASON_AUTO_ZERO.
//   7. Charging disabled (sysOff, ignition, OnOff, BMS, weather, IDLE stage)
//      -> MODE_DISABLED_RAMP.
//   8. MODE_NORMAL_AUTO_PID, NONE.
#include "core/modes.h"
#include "protection/tick_snapshot.h"

namespace xr {

struct ModeDecision {
  FieldControlMode mode = FieldControlMode::MODE_DISABLED_RAMP;
  Reason reason = Reason::NONE;
};

// Both in one pass (the two functions below call this).
ModeDecision selectFieldMode(const TickSnapshot& s);
FieldControlMode selectFieldControlMode(const TickSnapshot& s);
Reason selectFieldEventReason(const TickSnapshot& s);

// Reasons whose shutdown path is applyImmediateCut() (GPIO4 LOW this tick,
// no ramp, no cooldown): INA OV, hard OC, T3, RPM gate.
bool isImmediateCutReason(Reason r);
// Normal modes: the control law runs (AUTO PID, MANUAL duty, Limp Home 30 %).
bool isNormalMode(FieldControlMode m);

}  // namespace xr
