#pragma once
// Every variable of docs/control.md, exported per tick.
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
  bool bulkVoltageLimitActive = false;  // CV engaged at BulkVoltage inside BULK (this project's)
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

// Visits every field as f("name", value) — the one list the status JSON
// and any other exporter use, so a new field is exported by adding it here.
template <typename T, typename F>
void visitControlTelemetry(T& t, F&& f) {
  f("sysMode", t.sysMode);
  f("govMode", t.govMode);
  f("I_cap", t.I_cap);
  f("I_cmd", t.I_cmd);
  f("uTargetRaw", t.uTargetRaw);
  f("uTargetAmps", t.uTargetAmps);
  f("setpointCommand", t.setpointCommand);
  f("setpointLimited", t.setpointLimited);
  f("pidInput", t.pidInput);
  f("pidOutput", t.pidOutput);
  f("innerTermP", t.innerTermP);
  f("innerTermI", t.innerTermI);
  f("innerTermD", t.innerTermD);
  f("dutyRequest", t.dutyRequest);
  f("lastAppliedDuty", t.lastAppliedDuty);
  f("rpmMinDuty", t.rpmMinDuty);
  f("voltageControlActive", t.voltageControlActive);
  f("ChargingVoltageTarget", t.ChargingVoltageTarget);
  f("voltageTargetSlewed", t.voltageTargetSlewed);
  f("cv_I", t.cv_I);
  f("Icv", t.Icv);
  f("cv_I_track", t.cv_I_track);
  f("cv_I_aw_cap", t.cv_I_aw_cap);
  f("g_awState", t.g_awState);
  f("cvDSlope", t.cvDSlope);
  f("g_voltLoopActualIntervalMs", t.g_voltLoopActualIntervalMs);
  f("tempFiltered", t.tempFiltered);
  f("projectedTempF", t.projectedTempF);
  f("thermalSlopeFPerSec", t.thermalSlopeFPerSec);
  f("thermalPenaltyAmps", t.thermalPenaltyAmps);
  f("thermalPenaltyAmps_d", t.thermalPenaltyAmps_d);
  f("thermalHolding", t.thermalHolding);
  f("MeasuredAmps", t.MeasuredAmps);
  f("MeasuredAmps_filtered", t.MeasuredAmps_filtered);
  f("g_pidI_filtered", t.g_pidI_filtered);
  f("g_pidMA_N", t.g_pidMA_N);
  f("IBV_filtered", t.IBV_filtered);
  f("inStartupRamp", t.inStartupRamp);
  f("fastRiseActive", t.fastRiseActive);
  f("warmupActive", t.warmupActive);
  f("bulkVoltageLimitActive", t.bulkVoltageLimitActive);
  f("fastOvClampActive", t.fastOvClampActive);
  f("cvOvershootBypass", t.cvOvershootBypass);
  f("inBulkStage", t.inBulkStage);
  f("inAbsorptionStage", t.inAbsorptionStage);
  f("inFloatStage", t.inFloatStage);
  f("inIdleStage", t.inIdleStage);
  f("tailSuppressedByThermal", t.tailSuppressedByThermal);
  f("rebulkBlockedBySoc", t.rebulkBlockedBySoc);
  f("limpHome", t.limpHome);
  f("tuningRunning", t.tuningRunning);
  f("tuningHighPhase", t.tuningHighPhase);
  f("tuningScore", t.tuningScore);
  f("tuningLogCount", t.tuningLogCount);
  f("cvTuningRunning", t.cvTuningRunning);
  f("cvTuningScore", t.cvTuningScore);
  f("cvTuningSettleSec", t.cvTuningSettleSec);
  f("cvTuningLogCount", t.cvTuningLogCount);
  f("sysIDRunning", t.sysIDRunning);
  f("sysIDValid", t.sysIDValid);
  f("sysIDDutyOut", t.sysIDDutyOut);
  f("sysIDDeadTimeMs", t.sysIDDeadTimeMs);
  f("sysIDRiseTimeMs", t.sysIDRiseTimeMs);
  f("sysIDSlopeAps", t.sysIDSlopeAps);
}

}  // namespace xr
