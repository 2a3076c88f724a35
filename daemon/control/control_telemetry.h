#pragma once
// Every variable of field-control.md's diagram and tables, exported per tick.
// Owned by the control core; fields are added here as they are implemented.
#include "core/modes.h"

namespace xr {

struct ControlTelemetry {
  SysMode sysMode = SysMode::SYS_MODE_OFF;
  GovMode govMode = GovMode::GOV_NORMAL_SLEW;
  double I_cap = 0.0;       // getCapCurrentForRPM
  double I_cmd = 0.0;       // after penalty, MaxTableValue, battery ceiling, warm-up
  double uTargetRaw = 0.0;  // before fastOvCurrentCap (after MaintainMode / TuningMode)
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
  double thermalPenaltyAmps_d = 0.0;  // tempPID output before the slew
  bool thermalHolding = false;        // stale temperature: penalty held
  double MeasuredAmps = 0.0, MeasuredAmps_filtered = 0.0, g_pidI_filtered = 0.0, g_pidMA_N = 0.0;
  double IBV_filtered = 0.0;
  bool inStartupRamp = false;
  bool fastRiseActive = false;          // FastSetpointRiseRate window
  bool warmupActive = false;            // warm-up ceiling applying
  bool bulkVoltageLimitActive = false;  // CV engaged at BulkVoltage inside BULK (ours)
  bool fastOvClampActive = false;
  bool cvOvershootBypass = false;  // GOV_BYPASS_SLEW latch (CV overshoot)
  bool inBulkStage = true, inAbsorptionStage = false, inFloatStage = false, inIdleStage = false;
  bool tailSuppressedByThermal = false;
  bool rebulkBlockedBySoc = false;
  bool limpHome = false;
  // TuningMode / CVTuningMode.
  bool tuningRunning = false, tuningHighPhase = false;
  double tuningScore = 0.0;
  int tuningLogCount = 0;
  bool cvTuningRunning = false;
  double cvTuningScore = 0.0, cvTuningSettleSec = -1.0;
  int cvTuningLogCount = 0;
  // SystemID (Plant Delay).
  bool sysIDRunning = false, sysIDValid = false;
  double sysIDDutyOut = 0.0, sysIDDeadTimeMs = 0.0, sysIDRiseTimeMs = 0.0, sysIDSlopeAps = 0.0;
};

}  // namespace xr
