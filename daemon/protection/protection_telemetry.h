#pragma once
// State of every protection, exported per tick. Owned by daemon/protection;
// filled by ProtectionSupervisor::telemetry().
#include "core/modes.h"

namespace xr {

struct ProtectionTelemetry {
  ShutdownPhase shutdownPhase = ShutdownPhase::PHASE_NONE;
  bool nearBulk = false;
  double fastOvCurrentCap = 0.0;
  bool fastOvClampActive = false;
  bool inaOvervoltageLatched = false;
  bool lockoutActive = false;
  double lockoutRemainingS = 0.0;
  bool tempTaskAlarm = false;
  bool buzzer = false;
  Reason lastTripReason = Reason::NONE;
  double lastTripTimeS = 0.0;
  // Fast-OV supervisors (safeties-and-protections.md Groups 1/2/3, load dump).
  bool group1Active = false, group2Active = false, group3Active = false, loadDumpActive = false;
  double Vpred = 0.0;
  double dvdt = 0.0;     // V/s, EMA at DvdtAlpha
  double dBcurDt = 0.0;  // A/s, last accepted sample pair
  bool govBypassLatched = false;
  // Detector states.
  bool hardOvercurrent = false, tempCritical = false, rpmBelowMin = false;
  bool altHardShutdown = false, voltageDisagreeWarning = false, voltageDisagreeCritical = false,
       voltageImplausible = false;
  bool tempWarning = false, tempSustained = false, tempStale = false, currentStale = false;
  bool fieldCut = false;  // GPIO4 held LOW by the sequencer
  bool alarmLatched = false;
};

}  // namespace xr
