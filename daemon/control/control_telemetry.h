#pragma once
// Every variable of field-control.md's diagram and tables, exported per tick.
// Owned by the control core; fields are added here as they are implemented.
#include "core/modes.h"

namespace xr {

struct ControlTelemetry {
  SysMode sysMode = SysMode::SYS_MODE_OFF;
  GovMode govMode = GovMode::GOV_NORMAL_SLEW;
  double I_cap = 0.0;           // getCapCurrentForRPM
  double uTargetAmps = 0.0;
  double setpointCommand = 0.0;
  double setpointLimited = 0.0;
  double pidInput = 0.0;
  double pidOutput = 0.0;
  double innerTermP = 0.0, innerTermI = 0.0, innerTermD = 0.0;
  double dutyRequest = 0.0;
  double lastAppliedDuty = 0.0;
  double rpmMinDuty = 0.0;
  bool voltageControlActive = false;
  double ChargingVoltageTarget = 0.0;
  double voltageTargetSlewed = 0.0;
  double cv_I = 0.0, Icv = 0.0, cv_I_track = 0.0, cv_I_aw_cap = 0.0;
  int g_awState = 0;
  double cvDSlope = 0.0;
  double g_voltLoopActualIntervalMs = 0.0;
  double tempFiltered = 0.0, projectedTempF = 0.0, thermalSlopeFPerSec = 0.0;
  double thermalPenaltyAmps = 0.0;
  double MeasuredAmps = 0.0, MeasuredAmps_filtered = 0.0, g_pidI_filtered = 0.0, g_pidMA_N = 0.0;
  double IBV_filtered = 0.0;
  bool inStartupRamp = false;
};

}  // namespace xr
