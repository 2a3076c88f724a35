#pragma once
// TickSnapshot: the immutable state capture that mode selection reads
// (docs/control.md "Order of one tick" step 1, "Mode Priority
// Hierarchy"). selectFieldControlMode() / selectFieldEventReason() are pure
// functions of this struct and nothing else.
//
// Who fills what:
//   - `prot` is copied whole from ProtectionSupervisor::flags() right after
//     ProtectionSupervisor::updateDetectors() ran for this tick.
//   - everything else is filled by the control side (Regulator::step) from its
//     own state, the Params and the Inputs, BEFORE calling the selectors.
#include "core/modes.h"
#include "core/time.h"

namespace xr {

// What the protection detectors concluded this tick. Each flag already honours
// its own enable/ignore parameter (IgnoreTemperature, IgnoreRPM,
// INADisconnected); WHICH operating modes it acts in is decided by the
// selectors, not here.
struct ProtectionFlags {
  // Priority 1 (immediate cut). INA latch acts in every mode incl. Limp Home;
  // hard OC and T3 in AUTO and MANUAL.
  bool inaOvervoltageLatched = false;  // INA228 hardware ALERT software latch
  bool hardOvercurrent = false;        // MeasuredAmps > HardOCTripAmps for HardOCDebounceMs
  bool tempCritical = false;           // T3: TempToUse > TemperatureLimitF + TempCritExcess
  // RPM gate (immediate cut) in AUTO and MANUAL.
  bool rpmBelowMin = false;  // RPM < MinRPMForField (and !IgnoreRPM)

  // AUTO-only, critical ramp (phase 4 direct, then lockout).
  bool voltageDisagreeCritical = false;  // > 1/2/4 V for 3 s, or NaN / < 0.1 V at once
  bool voltageImplausible = false;       // both sensors outside the plausible range
  bool tempStale = false;                // T5
  bool currentStale = false;             // no fresh INA228 / CH1 sample in CurrentStaleMs

  // Immediate cut in every mode, then the lockout (a deviation: docs/deviations.md).
  bool altHardShutdown = false;  // IBV > AlternatorHardShutdownV
  // Every voltage sensor reads another bank size than the settings are for
  // (a 24 V file on a 12 V bank): every voltage threshold is wrong, so the
  // field is cut in every mode (docs/deviations.md "Bank size check").
  bool bankMismatch = false;
  // INADisconnected: AUTO refuses to run without voltage feedback.
  bool inaAbsent = false;

  // AUTO-only, warning ramp (phases 1-4, then lockout).
  bool voltageDisagreeWarning = false;  // > VoltageDisagreeThreshold for VoltageDisagreeTimeout
  bool tempWarning = false;             // T1
  bool tempSustained = false;           // T2: latched until reenable_field
  // A deviation (docs/deviations.md "Heat soak after an engine stop"): the engine
  // restarted with the alternator above TemperatureLimitF; the field stays
  // off until the running fan has cooled it to the limit.
  bool tempSoakHold = false;

  // A warning/critical ramp, once started, runs to its GPIO4 cut even if the
  // trigger clears meanwhile (otherwise a fault that clears because the duty
  // fell would never reach the lockout). Set by the supervisor, cleared when
  // the lockout begins or a normal mode is selected.
  bool rampLatched = false;
  FieldControlMode rampLatchedMode = FieldControlMode::MODE_WARNING_RAMP_AND_LOCKOUT;
  Reason rampLatchedReason = Reason::NONE;

  // Cooldown lockout (FIELD_COLLAPSE_DELAY) in progress.
  bool lockoutActive = false;

  // T4: TempTask heartbeat older than TEMP_TASK_TIMEOUT (buzzer only).
  bool tempTaskAlarm = false;
};

struct TickSnapshot {
  TimeNs now = 0;
  ProtectionFlags prot;

  // Operator modes.
  bool limpHome = false;    // Limp Home toggled on (command limp_home)
  bool manualMode = false;  // tick.manualMode: ManualMode param or sysMode MANUAL
  bool sysOff = false;      // operator "off" command (sysMode OFF)

  // Charging-enabled inputs, kept separate so the reason code can name the
  // one acting (MODE_DISABLED_RAMP, no alarm).
  bool ignitionOn = true;          // Inputs::ignitionOn
  bool OnOff = true;               // Params::OnOff
  bool bmsChargeEnabled = true;    // Inputs::bmsChargeEnabled
  bool weatherModeActive = false;  // weatherModeEnabled && currentWeatherMode
  bool idleStage = false;          // ChargeStage::IDLE (UseFloat = 0 after absorption)
  bool batteryCold = false;        // BatteryTemperatureGuard: below ChargeMinTempC (docs/batteries.md)
  bool batteryHot = false;         // above ChargeMaxTempC

  // MODE_LOCKOUT_RAMP also covers an auto-zero measurement (field must be off).
  bool autoZeroActive = false;
};

}  // namespace xr
