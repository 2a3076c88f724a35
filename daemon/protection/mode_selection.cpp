#include "protection/mode_selection.h"

namespace xr {
namespace {

using M = FieldControlMode;

// "Do not charge" orders that even Limp Home obeys.
Reason hardDisableReason(const TickSnapshot& s) {
  if (!s.ignitionOn) return Reason::REASON_IGNITION_OFF;
  if (!s.OnOff) return Reason::REASON_ONOFF_DISABLED;
  if (!s.bmsChargeEnabled) return Reason::REASON_BMS_DISABLED;
  // The battery's own temperature limits, as a BMS would enforce them
  // (docs/batteries.md): orders about the battery, obeyed in every mode.
  if (s.batteryCold) return Reason::REASON_BATTERY_COLD;
  if (s.batteryHot) return Reason::REASON_BATTERY_HOT;
  return Reason::NONE;
}

// Every reason charging is disabled (docs/protections.md MODE_DISABLED_RAMP:
// ignition off, OnOff = 0, BMS signal, weather mode; plus operator "off" and
// the IDLE stage, where docs/control.md sets chargingEnabled = false).
Reason disableReason(const TickSnapshot& s) {
  if (s.sysOff) return Reason::REASON_SYS_OFF;
  if (Reason r = hardDisableReason(s); r != Reason::NONE) return r;
  if (s.weatherModeActive) return Reason::REASON_WEATHER_MODE;
  if (s.idleStage) return Reason::REASON_IDLE_STAGE;
  return Reason::NONE;
}

bool latched(const ProtectionFlags& f, M m) { return f.rampLatched && f.rampLatchedMode == m; }

}  // namespace

ModeDecision selectFieldMode(const TickSnapshot& s) {
  const ProtectionFlags& f = s.prot;
  // 0. Added here: the bank is another size than the settings say, so every
  // voltage threshold (the hard shutdown's and the INA228 limit too) is
  // wrong: cut in every mode, and name the cause first — 12 V settings on a
  // 24 V bank also latch the INA228 alert, which is a symptom of it.
  if (f.bankMismatch) return {M::MODE_CRITICAL_RAMP, Reason::REASON_BANK_MISMATCH};
  // 0b. INA228 latch: all modes, Limp Home included (pre-gate).
  if (f.inaOvervoltageLatched) return {M::MODE_CRITICAL_RAMP, Reason::REASON_INA_OVERVOLTAGE};
  // 0c. Alternator hard shutdown: an immediate cut in every mode (a deviation, after
  // the original firmware's later versions; the specification's warning ramp went on
  // feeding a bank already over its trip for seconds).
  if (f.altHardShutdown) return {M::MODE_CRITICAL_RAMP, Reason::REASON_ALT_HARD_SHUTDOWN};
  // L. Limp Home bypasses the whole protection chain.
  if (s.limpHome) {
    if (Reason r = hardDisableReason(s); r != Reason::NONE) return {M::MODE_DISABLED_RAMP, r};
    return {M::MODE_LIMP_HOME, Reason::REASON_LIMP_HOME};
  }
  // 1. Priority 1 immediate cuts, AUTO and MANUAL.
  if (f.hardOvercurrent) return {M::MODE_CRITICAL_RAMP, Reason::REASON_HARD_OVERCURRENT};
  if (f.tempCritical) return {M::MODE_CRITICAL_RAMP, Reason::REASON_TEMP_CRITICAL};
  // 1b. RPM gate, AUTO and MANUAL.
  if (f.rpmBelowMin) return {M::MODE_DISABLED_RAMP, Reason::REASON_RPM_LOW};
  // 2. MANUAL: everything below is bypassed.
  if (s.manualMode) {
    if (Reason r = disableReason(s); r != Reason::NONE) return {M::MODE_DISABLED_RAMP, r};
    return {M::MODE_NORMAL_MANUAL, Reason::NONE};
  }
  // 3. Cooldown lockout: charging cannot resume whatever the faults do.
  if (f.lockoutActive) return {M::MODE_LOCKOUT_RAMP, Reason::REASON_LOCKOUT};
  // 4. Critical ramp.
  if (f.voltageDisagreeCritical) return {M::MODE_CRITICAL_RAMP, Reason::REASON_VOLTAGE_DISAGREE_CRITICAL};
  if (f.voltageImplausible) return {M::MODE_CRITICAL_RAMP, Reason::REASON_VOLTAGE_IMPLAUSIBLE};
  if (f.tempStale) return {M::MODE_CRITICAL_RAMP, Reason::REASON_TEMP_STALE};
  if (f.currentStale) return {M::MODE_CRITICAL_RAMP, Reason::REASON_CURRENT_STALE};
  if (latched(f, M::MODE_CRITICAL_RAMP)) return {M::MODE_CRITICAL_RAMP, f.rampLatchedReason};
  // 5. Warning ramp.
  if (f.tempSustained) return {M::MODE_WARNING_RAMP_AND_LOCKOUT, Reason::REASON_TEMP_SUSTAINED};
  if (f.tempWarning) return {M::MODE_WARNING_RAMP_AND_LOCKOUT, Reason::REASON_TEMP_WARNING};
  if (f.voltageDisagreeWarning)
    return {M::MODE_WARNING_RAMP_AND_LOCKOUT, Reason::REASON_VOLTAGE_DISAGREE_WARNING};
  if (latched(f, M::MODE_WARNING_RAMP_AND_LOCKOUT))
    return {M::MODE_WARNING_RAMP_AND_LOCKOUT, f.rampLatchedReason};
  // 5b. No INA228 (INADisconnected): AUTO has no voltage feedback and does
  // not run; MANUAL and Limp Home above still do.
  if (f.inaAbsent) return {M::MODE_DISABLED_RAMP, Reason::REASON_VOLTAGE_IMPLAUSIBLE};
  // 6. Auto-zero needs the field off.
  if (s.autoZeroActive) return {M::MODE_LOCKOUT_RAMP, Reason::REASON_AUTO_ZERO};
  // 7. Charging disabled: clean ramp, no alarm.
  if (Reason r = disableReason(s); r != Reason::NONE) return {M::MODE_DISABLED_RAMP, r};
  // 7b. Added here: a heat-soaked alternator cools before the field returns (a
  // clean hold, no alarm: nothing is wrong with it). After the disable
  // reasons, so an ignition that is off is named as such.
  if (f.tempSoakHold) return {M::MODE_DISABLED_RAMP, Reason::REASON_TEMP_SOAK};
  // 8. Normal.
  return {M::MODE_NORMAL_AUTO_PID, Reason::NONE};
}

FieldControlMode selectFieldControlMode(const TickSnapshot& s) { return selectFieldMode(s).mode; }
Reason selectFieldEventReason(const TickSnapshot& s) { return selectFieldMode(s).reason; }

bool isImmediateCutReason(Reason r) {
  return r == Reason::REASON_INA_OVERVOLTAGE || r == Reason::REASON_HARD_OVERCURRENT ||
         r == Reason::REASON_TEMP_CRITICAL || r == Reason::REASON_RPM_LOW ||
         r == Reason::REASON_ALT_HARD_SHUTDOWN || r == Reason::REASON_BANK_MISMATCH;
}

bool isNormalMode(FieldControlMode m) {
  return m == M::MODE_NORMAL_AUTO_PID || m == M::MODE_NORMAL_MANUAL || m == M::MODE_LIMP_HOME;
}

}  // namespace xr
