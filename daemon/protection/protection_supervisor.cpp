// ProtectionSupervisor: calls the parts in order and publishes what they
// concluded (flags for mode selection, telemetry).
#include "protection/protection_supervisor.h"

#include <algorithm>
#include <cstdint>

#include "core/alternator_temperature.h"

namespace xr {
namespace {

// Before the first sample of a voltage sensor has arrived, NaN means "not
// read yet", not "sensor dead" (docs/protections.md "First readings"). Two
// seconds covers the slowest first conversion (INA228 slow mode ~1.05 s)
// with margin.
constexpr std::int64_t kSensorBootGraceMs = 2000;

}  // namespace

ProtectionSupervisor::ProtectionSupervisor(const Params& p) : p_(p) {}

void ProtectionSupervisor::setParams(const Params& p) noexcept { p_ = p; }

void ProtectionSupervisor::updateDetectors(const Inputs& in, double MeasuredAmps, EventBatch& ev) noexcept {
  if (boot_ < 0) {
    boot_ = in.now;
    now_ = in.now;
  }
  prevNow_ = now_;
  now_ = in.now;
  seen_ = {in.IBV.value, in.Bcur.value, MeasuredAmps};
  const ProtectionLog lg = log(ev, sequencer_.mode());
  const double IBV = in.IBV.value, BatteryV = in.BatteryV.value;

  ina_.update({in.inaBusOvervoltage, IBV}, p_, lg);
  const bool notReadYet =
      (in.IBV.stamp == 0 || in.BatteryV.stamp == 0) && now_ - boot_ < fromMs(kSensorBootGraceMs);
  voltage_.update({IBV, BatteryV, notReadYet, ina_.latched(), ina_.suppressesDisagreement(now_)}, p_, lg);
  bank_.update({IBV, BatteryV}, p_, lg);
  // The RPM gate before the temperatures: the heat-soak rule needs to know
  // whether the engine turns this tick.
  rpm_.update({in.rpm.value, fieldResting_}, p_, lg);
  temp_.update({alternatorTemperature(in, p_.TempSource), in.tempTaskHeartbeat, boot_, rpm_.belowMin()}, p_,
               lg);
  current_.update({MeasuredAmps, in.altCurrentRaw.stamp, std::max(in.IBV.stamp, in.Bcur.stamp),
                   in.inaFastModeActive, boot_},
                  p_, lg);
  fastOv_.sample(in, p_);
  sequencer_.expireLockout(lg);
  publishFlags();
}

// What mode selection reads, from the parts that own it.
void ProtectionSupervisor::publishFlags() noexcept {
  ProtectionFlags& f = flags_;
  f.inaAbsent = p_.INADisconnected;
  f.inaOvervoltageLatched = ina_.latched();
  f.altHardShutdown = voltage_.altHardShutdown();
  f.voltageDisagreeWarning = voltage_.disagreeWarning();
  f.voltageDisagreeCritical = voltage_.disagreeCritical();
  f.voltageImplausible = voltage_.implausible();
  f.bankMismatch = bank_.mismatch();
  f.rpmBelowMin = rpm_.belowMin();
  f.tempSoakHold = temp_.soakHold();
  f.tempWarning = temp_.warning();
  f.tempSustained = temp_.sustained();
  f.tempCritical = temp_.critical();
  f.tempStale = temp_.stale();
  f.tempTaskAlarm = temp_.taskHung();
  f.hardOvercurrent = current_.hardOvercurrent();
  f.currentStale = current_.stale();
  sequencer_.publish(f);
}

ShutdownCommand ProtectionSupervisor::runShutdownPath(const ModeDecision& d, double lastAppliedDuty,
                                                      double rpmMinDuty, EventBatch& ev) noexcept {
  const ShutdownCommand c =
      sequencer_.update({d, lastAppliedDuty, rpmMinDuty, prevNow_}, p_, log(ev, d.mode));
  sequencer_.publish(flags_);
  return c;
}

bool ProtectionSupervisor::checkAlarms(bool effAnomalyAlarmActive, EventBatch& ev) noexcept {
  AlarmInput a;
  a.TempToUse = temp_.value();
  a.tempStale = temp_.stale();
  a.IBV = seen_.IBV;
  a.MeasuredAmps = seen_.MeasuredAmps;
  a.Bcur = seen_.Bcur;
  a.inaLatched = ina_.latched();
  a.tempTaskHung = temp_.taskHung();
  a.faultMode = sequencer_.faultAlarm();
  a.effAnomaly = effAnomalyAlarmActive;
  return alarms_.update(a, p_, log(ev, sequencer_.mode()));
}

// "T2 ... No auto-restart — field stays off until manual re-enable or reboot."
void ProtectionSupervisor::reenableField() noexcept {
  temp_.reenable();
  sequencer_.releaseLatch(Reason::REASON_TEMP_SUSTAINED);
  flags_.tempSustained = false;
  sequencer_.publish(flags_);
}

ProtectionTelemetry ProtectionSupervisor::telemetry() const noexcept {
  ProtectionTelemetry t;
  fillTelemetry(t);
  return t;
}

void ProtectionSupervisor::fillTelemetry(ProtectionTelemetry& t) const noexcept {
  const FastOvAction& fo = fastOv_.last();
  const ProtectionFlags& f = flags_;
  t.shutdownPhase = sequencer_.phase();
  t.nearBulk = fo.nearBulk;
  t.fastOvCurrentCap = fo.verdict.fastOvCurrentCap;
  t.fastOvClampActive = fo.verdict.fastOvClampActive;
  t.inaOvervoltageLatched = f.inaOvervoltageLatched;
  t.lockoutActive = f.lockoutActive;
  t.lockoutRemainingS = sequencer_.lockoutRemainingS(now_);
  t.tempTaskAlarm = f.tempTaskAlarm;
  t.buzzer = alarms_.buzzer();
  t.lastTripReason = lastTrip_.reason;
  t.lastTripTimeS = boot_ >= 0 ? toSec(lastTrip_.time - boot_) : 0.0;
  t.group1Active = fo.group1;
  t.group2Active = fo.group2;
  t.group3Active = fo.group3;
  t.loadDumpActive = fo.loadDump;
  t.Vpred = fastOv_.Vpred();
  t.dvdt = fastOv_.rates().dvdt();
  t.dBcurDt = fastOv_.rates().dBcurDt();
  t.govBypassLatched = fastOv_.bypassLatched();
  t.hardOvercurrent = f.hardOvercurrent;
  t.tempCritical = f.tempCritical;
  t.rpmBelowMin = f.rpmBelowMin;
  t.voltageDisagreeCritical = f.voltageDisagreeCritical;
  t.voltageImplausible = f.voltageImplausible;
  t.tempStale = f.tempStale;
  t.currentStale = f.currentStale;
  t.altHardShutdown = f.altHardShutdown;
  t.bankMismatch = f.bankMismatch;
  t.voltageDisagreeWarning = f.voltageDisagreeWarning;
  t.tempWarning = f.tempWarning;
  t.tempSustained = f.tempSustained;
  t.fieldCut = sequencer_.fieldCut();
  t.alarmLatched = alarms_.latched();
}

}  // namespace xr
