// ProtectionSupervisor::updateDetectors(): every trigger of
// docs/protections.md, with its sustained timer. Flags only: which
// mode each flag acts in is decided by selectFieldMode().
#include <algorithm>
#include <cmath>

#include "core/alternator_temperature.h"
#include "core/finite.h"
#include "params/constants.h"
#include "params/derived.h"
#include "protection/protection_supervisor.h"

namespace xr {
namespace {

// Not in the seeds: before the first sample of a voltage sensor has arrived,
// NaN means "not read yet", not "sensor dead". Two seconds covers the slowest
// first conversion (INA228 slow mode ~1.05 s) with margin.
constexpr std::int64_t kSensorBootGraceMs = 2000;

// Ours (docs/deviations.md "Bank size check"): how long every voltage sensor
// must read another bank size before the field is cut. Long enough to ride
// through a 24 V starter's cranking dip, short enough that a 24 V target on
// a 12 V bank cannot lift it far (the governor's slew needs seconds).
constexpr std::int64_t kBankMismatchHoldMs = 5000;

}  // namespace

bool ProtectionSupervisor::sustained(TimerState& t, bool cond, TimeNs hold) const noexcept {
  if (!cond) {
    t.since = -1;
    return false;
  }
  if (t.since < 0) t.since = now_;
  return now_ - t.since >= hold;
}

void ProtectionSupervisor::updateDetectors(const Inputs& in, double MeasuredAmps, EventBatch& ev) noexcept {
  if (boot_ < 0) {
    boot_ = in.now;
    now_ = in.now;
  }
  prevNow_ = now_;  // dtSec() = clamp(toSec(now_ - prevNow_), 0, 1), as it was stored here per tick
  now_ = in.now;
  IBV_ = in.IBV.value;
  BatteryV_ = in.BatteryV.value;
  Bcur_ = in.Bcur.value;
  MeasuredAmps_ = MeasuredAmps;
  rpm_ = in.rpm.value;
  if (in.inaFastModeActive && !inaFastModeActive_) inaFastSince_ = now_;
  inaFastModeActive_ = in.inaFastModeActive;

  updateInaLatch(in, ev);
  updateVoltageSensors(in, ev);
  updateBankMismatch(ev);
  updateRpmGate(ev);
  updateTemperature(in, ev);
  updateCurrent(in, MeasuredAmps, ev);
  updateFastSamples(in);

  // Cooldown lockout expiry ("After it elapses the system retries").
  if (flags_.lockoutActive && now_ >= lockoutUntil_) {
    flags_.lockoutActive = false;
    push(ev, EventCode::LockoutExpired, EventLevel::Info, Reason::REASON_LOCKOUT);
  }
}

// "INA228 Hardware ALERT — Software latch": evaluated on the CheckAlarms
// cadence (250 ms). Set when the driver reports the bus-overvoltage alert;
// release check 3 s after latching, then a definitive recheck every 10 s.
// The seed's 5 s new-event poll is tightened to every 250 ms check (the
// hardware has already cut GPIO4; the sooner the software agrees the better).
void ProtectionSupervisor::updateInaLatch(const Inputs& in, EventBatch& ev) noexcept {
  flags_.inaAbsent = p_.INADisconnected;
  if (p_.INADisconnected) {
    flags_.inaOvervoltageLatched = false;
    return;
  }
  // Ours: the alert is looked at on every tick the driver read DIAG_ALRT
  // (the chip's alert does not latch, so a 50 ms pulse polled every 250 ms
  // was missed 8 times in 10); the release checks keep the seed's cadence.
  if (!flags_.inaOvervoltageLatched) {
    if (in.inaBusOvervoltage) {
      flags_.inaOvervoltageLatched = true;
      inaLatchedAt_ = now_;
      inaNextRelease_ = now_ + fromMs(k::INA_LATCH_RELEASE_CHECK_MS);
      lastTripReason_ = Reason::REASON_INA_OVERVOLTAGE;
      lastTripTime_ = now_;
      push(ev, EventCode::InaLatchSet, EventLevel::Critical, Reason::REASON_INA_OVERVOLTAGE, IBV_,
           voltageHardwareLimit(p_));
    }
  } else if (now_ >= inaNextRelease_) {
    if (!in.inaBusOvervoltage) {
      flags_.inaOvervoltageLatched = false;
      inaClearedAt_ = now_;
      push(ev, EventCode::InaLatchCleared, EventLevel::Warning, Reason::REASON_INA_OVERVOLTAGE, IBV_,
           toSec(now_ - inaLatchedAt_));
    } else {
      inaNextRelease_ = now_ + fromMs(k::INA_LATCH_RECHECK_MS);
    }
  }
}

// Alternator hard shutdown, disagreement warning/critical, implausibility.
void ProtectionSupervisor::updateVoltageSensors(const Inputs& in, EventBatch& ev) noexcept {
  // Alternator Hard Shutdown: IBV > AlternatorHardShutdownV.
  const double hs = alternatorHardShutdownV(p_);
  flags_.altHardShutdown = finite(IBV_) && IBV_ > hs;
  // Co-firing with the INA228 alert: one log line (InaLatchSet), not two.
  if (!(flags_.altHardShutdown && flags_.inaOvervoltageLatched))
    edge(evAltHs_, flags_.altHardShutdown, Reason::REASON_ALT_HARD_SHUTDOWN, IBV_, hs, ev, EventLevel::Error);

  const bool inaUsable = !p_.INADisconnected;
  const bool notReadYet =
      (in.IBV.stamp == 0 || in.BatteryV.stamp == 0) && now_ - boot_ < fromMs(kSensorBootGraceMs);
  const bool suppress = flags_.inaOvervoltageLatched ||
                        (inaClearedAt_ >= 0 && now_ - inaClearedAt_ < fromMs(k::INA_OV_DISAGREE_SUPPRESS_MS));
  bool disW = false, disC = false, impl = false;
  if (inaUsable && !notReadYet) {
    if (!suppress) {
      const bool dead =
          !finite(BatteryV_) || !finite(IBV_) || BatteryV_ < k::SENSOR_DEAD_V || IBV_ < k::SENSOR_DEAD_V;
      const double diff = dead ? 0.0 : std::fabs(BatteryV_ - IBV_);
      // NaN / < 0.1 V: critical at once, no debounce.
      disC = sustained(disagreeCritT_, !dead && diff > criticalDisagreementThreshold(p_),
                       fromMs(k::VoltageDisagreeCriticalTimeoutMs)) ||
             dead;
      disW = sustained(disagreeWarnT_, !dead && diff > p_.VoltageDisagreeThreshold,
                       fromSec(p_.VoltageDisagreeTimeout));
    }
    const VoltageRange range = plausibleVoltageRange(p_);
    auto outside = [&](double v) { return !finite(v) || v < range.min || v > range.max; };
    impl = outside(IBV_) && outside(BatteryV_);  // single-sensor implausibility passes
  }
  if (!inaUsable || notReadYet || suppress) {
    disagreeWarnT_.since = -1;
    disagreeCritT_.since = -1;
  }
  // Seed console wording for either level.
  if ((disW && !evDisW_.logged) || (disC && !evDisC_.logged))
    push(ev, EventCode::VoltageDisagreement, disC ? EventLevel::Critical : EventLevel::Error,
         disC ? Reason::REASON_VOLTAGE_DISAGREE_CRITICAL : Reason::REASON_VOLTAGE_DISAGREE_WARNING, BatteryV_,
         IBV_);
  edge(evDisW_, disW, Reason::REASON_VOLTAGE_DISAGREE_WARNING, BatteryV_, IBV_, ev, EventLevel::Error, false);
  edge(evDisC_, disC, Reason::REASON_VOLTAGE_DISAGREE_CRITICAL, BatteryV_, IBV_, ev, EventLevel::Critical,
       false);
  edge(evImpl_, impl, Reason::REASON_VOLTAGE_IMPLAUSIBLE, IBV_, BatteryV_, ev, EventLevel::Critical);
  flags_.voltageDisagreeWarning = disW;
  flags_.voltageDisagreeCritical = disC;
  flags_.voltageImplausible = impl;
}

// Bank size check: every live voltage sensor (IBV unless INADisconnected,
// BatteryV) reads a bank size other than BulkVoltage's (the one 18/36 V
// rule, params/derived.h). A dead sensor (< SENSOR_DEAD_V) is left to the
// disagreement and implausibility detectors.
void ProtectionSupervisor::updateBankMismatch(EventBatch& ev) noexcept {
  const SystemClass configured = systemClass(p_);
  int live = 0, other = 0;
  double shown = 0.0;
  auto look = [&](double v) {
    if (!finite(v) || v < k::SENSOR_DEAD_V) return;
    ++live;
    if (bankClassOfVoltage(v) != configured) {
      ++other;
      shown = v;
    }
  };
  if (!p_.INADisconnected) look(IBV_);
  look(BatteryV_);
  flags_.bankMismatch = sustained(bankMismatchT_, live > 0 && other == live, fromMs(kBankMismatchHoldMs));
  edge(evBank_, flags_.bankMismatch, Reason::REASON_BANK_MISMATCH, shown, nominalVoltage(configured), ev,
       EventLevel::Critical);
}

// T1, T2, T3 (IgnoreTemperature), T4 and T5 (not ignorable, see docs).
void ProtectionSupervisor::updateTemperature(const Inputs& in, EventBatch& ev) noexcept {
  const Reading& tr = alternatorTemperature(in, p_.TempSource);
  TempToUse_ = tr.value;
  const bool fresh = temperatureFresh(tr.value, tr.stamp, now_);
  // T5: never read after 60 s of uptime; older than 20 s; NaN / out of range.
  const bool stale = tr.stamp == 0 ? (now_ - boot_ > fromMs(k::TEMP_BOOT_GRACE_MS)) : !fresh;
  tempStaleRaw_ = stale;
  const bool usable = fresh && !p_.IgnoreTemperature;
  const double t = tr.value;

  // Ours (docs/deviations.md "Heat soak after an engine stop"):
  // with the engine stopped the field is off and the fan still, so heat
  // stored in the windings lifts the case; the field caused none of that
  // rise and can cool none of it, so T1/T2 do not count it. An engine that
  // restarts above TemperatureLimitF keeps the field off until the running
  // fan has cooled the case to the limit; T1/T2 count again from then. T3
  // and T5 are unchanged in every state.
  // The RPM gate alone says "stopped": an ignition that is off with the tach
  // still turning keeps the seed's T1 (DisabledRamp.WarningDuringDisabled...).
  const bool engineStopped = flags_.rpmBelowMin;
  const bool aboveLimit = usable && t > p_.TemperatureLimitF;
  flags_.tempSoakHold = aboveLimit && (engineStopped || flags_.tempSoakHold);
  const bool holding = flags_.tempSoakHold && !engineStopped;  // acting on the field now
  if (holding && !evSoak_.logged) {
    push(ev, EventCode::ProtectionTrip, EventLevel::Warning, Reason::REASON_TEMP_SOAK, t,
         p_.TemperatureLimitF);
    evSoak_.logged = true;
  } else if (!flags_.tempSoakHold && evSoak_.logged) {
    push(ev, EventCode::ProtectionClear, EventLevel::Info, Reason::REASON_TEMP_SOAK, t, p_.TemperatureLimitF);
    evSoak_.logged = false;
  }
  const bool t1 =
      usable && !engineStopped && !flags_.tempSoakHold && t > p_.TemperatureLimitF + p_.TempWarnExcess;
  // Ours: a T3 that fired is not released by a reading going stale or out
  // of range (MANUAL has no T5 to stop it); only a usable cooler reading does.
  const bool t3 =
      usable ? t > p_.TemperatureLimitF + p_.TempCritExcess : flags_.tempCritical && !p_.IgnoreTemperature;
  // T2: the T1 condition held continuously; latched until reenable_field.
  if (sustained(t1T_, t1, fromSec(p_.TempSustainedTimeout)) && !flags_.tempSustained) {
    flags_.tempSustained = true;
    lastTripReason_ = Reason::REASON_TEMP_SUSTAINED;
    lastTripTime_ = now_;
    push(ev, EventCode::ProtectionTrip, EventLevel::Error, Reason::REASON_TEMP_SUSTAINED, t,
         p_.TemperatureLimitF + p_.TempWarnExcess);
  }
  edge(evT1_, t1, Reason::REASON_TEMP_WARNING, t, p_.TemperatureLimitF + p_.TempWarnExcess, ev,
       EventLevel::Error);
  edge(evT3_, t3, Reason::REASON_TEMP_CRITICAL, t, p_.TemperatureLimitF + p_.TempCritExcess, ev,
       EventLevel::Critical);
  flags_.tempWarning = t1;
  flags_.tempCritical = t3;

  if (stale && !evT5_.logged)
    push(ev, EventCode::TempSensorStale, EventLevel::Error, Reason::REASON_TEMP_STALE, t);
  edge(evT5_, stale, Reason::REASON_TEMP_STALE, t, 0.0, ev, EventLevel::Error, false);
  flags_.tempStale = stale;

  // T4: TempTask heartbeat (buzzer only). Uptime counts as a heartbeat at boot.
  const TimeNs hb = std::max(in.tempTaskHeartbeat, boot_);
  const bool hung = now_ - hb > fromMs(k::TEMP_TASK_TIMEOUT);
  if (hung && !evT4_.logged)
    push(ev, EventCode::TempTaskHung, EventLevel::Critical, Reason::NONE, toSec(now_ - hb));
  evT4_.logged = hung;
  flags_.tempTaskAlarm = hung;
}

// The RPM gate. Before the temperature detectors, which need to know
// whether the engine turns this tick (the heat-soak rule).
void ProtectionSupervisor::updateRpmGate(EventBatch& ev) noexcept {
  // RPM < MinRPMForField; an unknown RPM counts as below (field stays off).
  // Ours: a resting field (control's full-bank rest) quiets a stator tach;
  // during the rest and RPM_REST_GRACE_MS after, an RPM that was fine when
  // the rest began still counts (docs/deviations.md "Full bank at light load").
  const bool rpmLive = finite(rpm_) && rpm_ >= p_.MinRPMForField;
  if (fieldResting_ && !wasResting_) rpmOkAtRestStart_ = !flags_.rpmBelowMin;
  if (!fieldResting_ && wasResting_) restEndedAt_ = now_;
  wasResting_ = fieldResting_;
  const bool restHold =
      rpmOkAtRestStart_ &&
      (fieldResting_ || (restEndedAt_ >= 0 && now_ - restEndedAt_ < fromMs(k::RPM_REST_GRACE_MS)));
  flags_.rpmBelowMin = !p_.IgnoreRPM && !rpmLive && !restHold;
  // Before the first engine-speed reading the field stays off as above, but
  // nothing "tripped": the event waits for a reading that is really low
  // (docs/protections.md "First readings").
  if (finite(rpm_)) rpmEverRead_ = true;
  if (rpmEverRead_ || !flags_.rpmBelowMin)
    edge(evRpm_, flags_.rpmBelowMin, Reason::REASON_RPM_LOW, rpm_, p_.MinRPMForField, ev, EventLevel::Info);
}

// Hard overcurrent, current data stale.
void ProtectionSupervisor::updateCurrent(const Inputs& in, double MeasuredAmps, EventBatch& ev) noexcept {
  const double trip = hardOCTripAmps(p_);
  flags_.hardOvercurrent =
      sustained(hardOcT_, finite(MeasuredAmps) && MeasuredAmps > trip, fromMs(p_.HardOCDebounceMs));
  edge(evHardOc_, flags_.hardOvercurrent, Reason::REASON_HARD_OVERCURRENT, MeasuredAmps, trip, ev,
       EventLevel::Critical);

  // Current data stale (our definition, docs/protections.md): no fresh CH1
  // sample for CurrentStaleMs, or no fresh INA228 sample for CurrentStaleMs
  // in fast mode / CurrentStaleMs + 2 slow periods in slow mode (field off,
  // ~1.05 s conversions) and for one slow period after switching to fast.
  const TimeNs win = fromMs(p_.CurrentStaleMs);
  auto staleOf = [&](TimeNs stamp, TimeNs window) { return now_ - (stamp != 0 ? stamp : boot_) > window; };
  const bool ch1Stale = staleOf(in.altCurrentRaw.stamp, win);
  const bool settledFast =
      inaFastModeActive_ && inaFastSince_ >= 0 && now_ - inaFastSince_ >= fromMs(k::INA_SLOW_INTERVAL_MS);
  const TimeNs inaWin = settledFast ? win : win + 2 * fromMs(k::INA_SLOW_INTERVAL_MS);
  const bool inaStale = !p_.INADisconnected && staleOf(std::max(in.IBV.stamp, in.Bcur.stamp), inaWin);
  flags_.currentStale = ch1Stale || inaStale;
  edge(evCur_, flags_.currentStale, Reason::REASON_CURRENT_STALE, ch1Stale ? 1.0 : 0.0, inaStale ? 1.0 : 0.0,
       ev, EventLevel::Critical);
}

// Fresh INA228 samples feed the Group 1 dv/dt EMA and the load-dump dBcur/dt.
// "dvdt sample window: 1–100 ms between INA samples ... slow mode rejected —
// dvdt holds last value."
void ProtectionSupervisor::updateFastSamples(const Inputs& in) noexcept {
  if (in.IBV.fresh && in.IBV.stamp != lastIbvStamp_ && finite(in.IBV.value)) {
    if (lastIbvStamp_ != 0 && finite(lastIbvSample_)) {
      const double dt = toSec(in.IBV.stamp - lastIbvStamp_);
      if (dt >= k::DVDT_MIN_SAMPLE_S && dt <= k::DVDT_MAX_SAMPLE_S) {
        const double raw = (in.IBV.value - lastIbvSample_) / dt;
        dvdt_ += p_.DvdtAlpha * (raw - dvdt_);
      }
    }
    lastIbvSample_ = in.IBV.value;
    lastIbvStamp_ = in.IBV.stamp;
  }
  loadDumpFiredThisSample_ = false;
  if (in.Bcur.fresh && in.Bcur.stamp != lastBcurStamp_ && finite(in.Bcur.value)) {
    bool accepted = false;
    if (lastBcurStamp_ != 0 && finite(lastBcurSample_)) {
      const double dt = toSec(in.Bcur.stamp - lastBcurStamp_);
      if (dt >= k::DVDT_MIN_SAMPLE_S && dt <= k::DVDT_MAX_SAMPLE_S) {
        dBcurDt_ = (in.Bcur.value - lastBcurSample_) / dt;
        accepted = true;
      }
    }
    if (accepted) {
      // Three tiers: 1 sample over Thresh1, 2 over Thresh, 3 over Thresh3.
      ldCount1_ = dBcurDt_ > p_.LoadDumpDtThresh1 ? ldCount1_ + 1 : 0;
      ldCount2_ = dBcurDt_ > p_.LoadDumpDtThresh ? ldCount2_ + 1 : 0;
      ldCount3_ = dBcurDt_ > p_.LoadDumpDtThresh3 ? ldCount3_ + 1 : 0;
      loadDumpFiredThisSample_ = ldCount1_ >= 1 || ldCount2_ >= 2 || ldCount3_ >= 3;
    } else {
      ldCount1_ = ldCount2_ = ldCount3_ = 0;
    }
    lastBcurSample_ = in.Bcur.value;
    lastBcurStamp_ = in.Bcur.stamp;
  }
}

}  // namespace xr
