#pragma once
// What the control law's parts read each tick: the corrected sensors, and
// what the fast over-voltage supervisors decided (so the law is testable
// without protection types).
#include "core/inputs.h"

namespace xr {

// Sensor values of this tick, already corrected (auto-zero, shunt gain).
struct ControlSensors {
  TimeNs now = 0;
  bool ch1Fresh = false;           // control work fires on fresh CH1
  double MeasuredAmps = kNoValue;  // CH1 - DynamicAltCurrentZero
  double IBV = kNoValue;
  bool ibvFresh = false;
  double Bcur = kNoValue;  // INA228 x DynamicShuntGainFactor (never Victron: MaintainMode)
  double rpm = kNoValue;
  double TempToUse = kNoValue;  // per TempSource
  TimeNs tempStamp = 0;
  double SOC_percent = kNoValue;
  bool socKnown = true;  // false while the battery monitor's SoC is only a guess (no SOC gating then)
  // Battery temperature current cap (cold ramp, no temperature).
  double batteryChargeCapA = 1e300;
};

// What the fast-OV supervisors (Groups 1/2/3, load dump) decided this tick.
struct FastOvApply {
  double fastOvCurrentCap = 1e300;  // clamp on uTargetAmps
  bool fastOvClampActive = false;
  bool setCvI = false;  // Snap / Bleed / Reseed
  double cv_I = 0.0;
  bool zeroSetpointLimited = false;  // load dump
  bool forceBypassSlew = false;
  bool sensorFailureBypass = false;  // !voltagePlausible || voltageDisagreementCritical
};

}  // namespace xr
