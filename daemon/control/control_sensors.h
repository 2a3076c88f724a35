#pragma once
// What the control law's parts read each tick: the corrected sensors. What
// the fast over-voltage supervisors decided comes in beside them, as the
// FastOvVerdict of core/fast_ov_verdict.h.
#include "core/fast_ov_verdict.h"
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
  // The bus voltage is implausible or the two voltages disagree critically:
  // the governor bypasses its slew (docs/control.md "Governor").
  bool sensorFailureBypass = false;
};

}  // namespace xr
