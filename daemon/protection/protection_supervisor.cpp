// ProtectionSupervisor: construction, parameters, commands, telemetry and the
// small shared helpers. The detectors, the shutdown sequencer, the fast-OV
// supervisors and CheckAlarms live in their own files.
#include "protection/protection_supervisor.h"

#include <algorithm>

#include "params/constants.h"
#include "params/derived.h"

namespace xr {

ProtectionSupervisor::ProtectionSupervisor(const Params& p) : p_(p) { alarmMsgAt_.fill(-1); }

void ProtectionSupervisor::setParams(const Params& p) noexcept { p_ = p; }

void ProtectionSupervisor::push(EventBatch& ev, EventCode c, EventLevel l, Reason r, double a, double b,
                                int detail) const noexcept {
  ev.push(makeEvent(now_, l, c, r, a, b, detail, lastMode_));
}

// Trip / clear events of one detector: the trip on its rising edge, the
// clear once the condition has stayed false for kEventClearHold (a re-trip
// inside that window is the same event, not a new one).
void ProtectionSupervisor::edge(EventEdge& e, bool now, Reason r, double a, double b, EventBatch& ev,
                                EventLevel level, bool logTrip) noexcept {
  if (now) {
    e.falseSince = -1;
    if (e.logged) return;
    e.logged = true;
    lastTripReason_ = r;
    lastTripTime_ = now_;
    if (logTrip) push(ev, EventCode::ProtectionTrip, level, r, a, b);
    return;
  }
  if (!e.logged) return;
  if (e.falseSince < 0) e.falseSince = now_;
  if (now_ - e.falseSince < kEventClearHold) return;
  e.logged = false;
  e.falseSince = -1;
  push(ev, EventCode::ProtectionClear, EventLevel::Info, r, a, b);
}

// "T2 ... No auto-restart — field stays off until manual re-enable or reboot."
void ProtectionSupervisor::reenableField() noexcept {
  flags_.tempSustained = false;
  t1T_.since = -1;  // the sustained timer restarts from the re-enable
  if (flags_.rampLatched && flags_.rampLatchedReason == Reason::REASON_TEMP_SUSTAINED)
    flags_.rampLatched = false;
}

void ProtectionSupervisor::resetAlarmLatch() noexcept { alarmLatched_ = false; }

void ProtectionSupervisor::acknowledgeAlarm() noexcept {
  ackRows_ = alarmRowOn_;
  ackActive_ = true;
  ackQuietSince_ = -1;
  alarmLatched_ = false;
  nextAlarmCheck_ = now_;  // quiet at the next tick, not up to 250 ms later
}

ProtectionTelemetry ProtectionSupervisor::telemetry() const noexcept {
  ProtectionTelemetry t;
  fillTelemetry(t);
  return t;
}

void ProtectionSupervisor::fillTelemetry(ProtectionTelemetry& t) const noexcept {
  t.shutdownPhase = phase_;
  t.nearBulk = lastFastOv_.nearBulk;
  t.fastOvCurrentCap = lastFastOv_.fastOvCurrentCap;
  t.fastOvClampActive = lastFastOv_.fastOvClampActive;
  t.inaOvervoltageLatched = flags_.inaOvervoltageLatched;
  t.lockoutActive = flags_.lockoutActive;
  t.lockoutRemainingS = flags_.lockoutActive ? std::max(0.0, toSec(lockoutUntil_ - now_)) : 0.0;
  t.tempTaskAlarm = flags_.tempTaskAlarm;
  t.buzzer = buzzer_;
  t.lastTripReason = lastTripReason_;
  t.lastTripTimeS = boot_ >= 0 ? toSec(lastTripTime_ - boot_) : 0.0;
  t.group1Active = lastFastOv_.group1;
  t.group2Active = lastFastOv_.group2;
  t.group3Active = lastFastOv_.group3;
  t.loadDumpActive = lastFastOv_.loadDump;
  t.Vpred = Vpred_;
  t.dvdt = dvdt_;
  t.dBcurDt = dBcurDt_;
  t.govBypassLatched = govBypassLatched_;
  t.hardOvercurrent = flags_.hardOvercurrent;
  t.tempCritical = flags_.tempCritical;
  t.rpmBelowMin = flags_.rpmBelowMin;
  t.voltageDisagreeCritical = flags_.voltageDisagreeCritical;
  t.voltageImplausible = flags_.voltageImplausible;
  t.tempStale = flags_.tempStale;
  t.currentStale = flags_.currentStale;
  t.altHardShutdown = flags_.altHardShutdown;
  t.bankMismatch = flags_.bankMismatch;
  t.voltageDisagreeWarning = flags_.voltageDisagreeWarning;
  t.tempWarning = flags_.tempWarning;
  t.tempSustained = flags_.tempSustained;
  t.fieldCut = fieldCut_;
  t.alarmLatched = alarmLatched_;
}

}  // namespace xr
