// TemperatureChecks::update(): T1 to T5 and the heat-soak hold.
#include "protection/temperature_checks.h"

#include <algorithm>

#include "core/alternator_temperature.h"
#include "params/constants.h"

namespace xr {

void TemperatureChecks::update(const TemperatureChecksInput& in, const Params& p,
                               const ProtectionLog& log) noexcept {
  const TimeNs now = log.now();
  value_ = in.temp.value;
  const bool fresh = temperatureFresh(in.temp.value, in.temp.stamp, now);
  // T5: never read after the boot grace; older than 20 s; NaN / out of range.
  const bool stale = in.temp.stamp == 0 ? (now - in.boot > fromMs(k::TEMP_BOOT_GRACE_MS)) : !fresh;
  const bool usable = fresh && !p.IgnoreTemperature;
  updateSoak(value_, usable, in.engineStopped, p, log);
  updateLimits(value_, usable, in.engineStopped, p, log);

  if (stale && !evT5_.logged)
    log.push(EventCode::TempSensorStale, EventLevel::Error, Reason::REASON_TEMP_STALE, value_);
  evT5_.update(stale, Reason::REASON_TEMP_STALE, value_, 0.0, log, EventLevel::Error, false);
  t5_ = stale;

  // T4: TempTask heartbeat (buzzer only). Uptime counts as a heartbeat at boot.
  const TimeNs hb = std::max(in.tempTaskHeartbeat, in.boot);
  const bool hung = now - hb > fromMs(k::TEMP_TASK_TIMEOUT);
  if (hung && !t4Logged_)
    log.push(EventCode::TempTaskHung, EventLevel::Critical, Reason::NONE, toSec(now - hb));
  t4Logged_ = hung;
  t4_ = hung;
}

// With the engine stopped the field is off and the fan still, so heat stored
// in the windings lifts the case; the field caused none of that rise and can
// cool none of it, so T1/T2 do not count it. An engine that restarts above
// TemperatureLimitF keeps the field off until the running fan has cooled the
// case to the limit; T1/T2 count again from then. T3 and T5 are unchanged in
// every state (docs/deviations.md "Heat soak after an engine stop"). The RPM
// gate alone says "stopped": an ignition that is off with the tach still
// turning keeps T1.
void TemperatureChecks::updateSoak(double t, bool usable, bool engineStopped, const Params& p,
                                   const ProtectionLog& log) noexcept {
  const bool aboveLimit = usable && t > p.TemperatureLimitF;
  soakHold_ = aboveLimit && (engineStopped || soakHold_);
  const bool holding = soakHold_ && !engineStopped;  // acting on the field now
  if (holding && !soakLogged_) {
    log.push(EventCode::ProtectionTrip, EventLevel::Warning, Reason::REASON_TEMP_SOAK, t,
             p.TemperatureLimitF);
    soakLogged_ = true;
  } else if (!soakHold_ && soakLogged_) {
    log.push(EventCode::ProtectionClear, EventLevel::Info, Reason::REASON_TEMP_SOAK, t, p.TemperatureLimitF);
    soakLogged_ = false;
  }
}

// T1, T2 (T1 sustained, latched) and T3.
void TemperatureChecks::updateLimits(double t, bool usable, bool engineStopped, const Params& p,
                                     const ProtectionLog& log) noexcept {
  const double warnAt = p.TemperatureLimitF + p.TempWarnExcess;
  const double critAt = p.TemperatureLimitF + p.TempCritExcess;
  const bool t1 = usable && !engineStopped && !soakHold_ && t > warnAt;
  // A T3 that fired is not released by a reading going stale or out of range
  // (MANUAL has no T5 to stop it); only a usable cooler reading does.
  const bool t3 = usable ? t > critAt : t3_ && !p.IgnoreTemperature;
  if (t1Held_.update(t1, log.now(), fromSec(p.TempSustainedTimeout)) && !t2_) {
    t2_ = true;
    log.noteTrip(Reason::REASON_TEMP_SUSTAINED);
    log.push(EventCode::ProtectionTrip, EventLevel::Error, Reason::REASON_TEMP_SUSTAINED, t, warnAt);
  }
  evT1_.update(t1, Reason::REASON_TEMP_WARNING, t, warnAt, log, EventLevel::Error);
  evT3_.update(t3, Reason::REASON_TEMP_CRITICAL, t, critAt, log, EventLevel::Critical);
  t1_ = t1;
  t3_ = t3;
}

void TemperatureChecks::reenable() noexcept {
  t2_ = false;
  t1Held_.reset();  // the sustained timer restarts from the re-enable
}

}  // namespace xr
