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
  // Fast-OV supervisors (docs/protections.md Groups 1/2/3, load dump).
  bool group1Active = false, group2Active = false, group3Active = false, loadDumpActive = false;
  double Vpred = 0.0;
  double dvdt = 0.0;     // V/s, EMA at DvdtAlpha
  double dBcurDt = 0.0;  // A/s, last accepted sample pair
  // Detector states, declared in ProtectionFlags' order (tick_snapshot.h) so
  // the per-tick copy compiles to a few wide moves (exporters go by name
  // through visitProtectionTelemetry, whose order is the exported one).
  bool hardOvercurrent = false, tempCritical = false, rpmBelowMin = false;
  bool voltageDisagreeCritical = false, voltageImplausible = false, tempStale = false, currentStale = false;
  bool altHardShutdown = false, bankMismatch = false, voltageDisagreeWarning = false, tempWarning = false,
       tempSustained = false;
  bool fieldCut = false;  // GPIO4 held LOW by the sequencer
  bool alarmLatched = false;
  bool govBypassLatched = false;  // fast-OV (declared here to keep the detector block aligned)
};

// Visits every field as f("name", value) — the one list the status JSON
// and any other exporter use, so a new field is exported by adding it here.
template <typename T, typename F>
void visitProtectionTelemetry(T& t, F&& f) {
  f("shutdownPhase", t.shutdownPhase);
  f("nearBulk", t.nearBulk);
  f("fastOvCurrentCap", t.fastOvCurrentCap);
  f("fastOvClampActive", t.fastOvClampActive);
  f("inaOvervoltageLatched", t.inaOvervoltageLatched);
  f("lockoutActive", t.lockoutActive);
  f("lockoutRemainingS", t.lockoutRemainingS);
  f("tempTaskAlarm", t.tempTaskAlarm);
  f("buzzer", t.buzzer);
  f("lastTripReason", t.lastTripReason);
  f("lastTripTimeS", t.lastTripTimeS);
  f("group1Active", t.group1Active);
  f("group2Active", t.group2Active);
  f("group3Active", t.group3Active);
  f("loadDumpActive", t.loadDumpActive);
  f("Vpred", t.Vpred);
  f("dvdt", t.dvdt);
  f("dBcurDt", t.dBcurDt);
  f("govBypassLatched", t.govBypassLatched);
  f("hardOvercurrent", t.hardOvercurrent);
  f("tempCritical", t.tempCritical);
  f("rpmBelowMin", t.rpmBelowMin);
  f("altHardShutdown", t.altHardShutdown);
  f("bankMismatch", t.bankMismatch);
  f("voltageDisagreeWarning", t.voltageDisagreeWarning);
  f("voltageDisagreeCritical", t.voltageDisagreeCritical);
  f("voltageImplausible", t.voltageImplausible);
  f("tempWarning", t.tempWarning);
  f("tempSustained", t.tempSustained);
  f("tempStale", t.tempStale);
  f("currentStale", t.currentStale);
  f("fieldCut", t.fieldCut);
  f("alarmLatched", t.alarmLatched);
}

}  // namespace xr
