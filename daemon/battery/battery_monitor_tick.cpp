// BatteryMonitor's tick after the control step (docs/batteries.md,
// docs/architecture.md "Battery monitor"): the battery sample each part
// gets, the SoC interval, a full charge, the rest re-anchor and the health
// figures, in the order the parts must run.
#include <cmath>

#include "battery/battery_monitor.h"
#include "battery/monitor_helpers.h"
#include "core/freshness.h"
#include "params/constants.h"
#include "params/derived.h"

namespace xr {

using namespace battery_detail;

void BatteryMonitor::updateBatterySoc(const Inputs& in, double measuredAltAmps, EventBatch& ev) noexcept {
  if (!started_) startTimers(in.now);
  const double dt = in.now > lastTick_ ? toSec(in.now - lastTick_) : 0.0;
  lastTick_ = in.now;

  // Latest values (zero-order hold over the tick just ended).
  const double V = getBatteryVoltage(in);
  const bool vOk = finite(V) && in.IBV.stamp != 0;
  double I = 0.0;
  bool iOk = false;
  const bool victron = usingVictronCurrent(in);
  if (victron) {
    I = in.VictronCurrent.value;
    iOk = true;
  } else if (usable(in.Bcur, in.now, battery_k::INA_STALE_FOR_SOC_MS)) {
    I = correctedBcur(in.Bcur.value);
    iOk = true;
  }
  if (vOk) lastValidVoltage_ = V;
  batteryCurrentForSoC_ = iOk ? I : 0.0;
  socInputsValid_ = iOk && vOk;
  usingVictron_ = victron;

  if (dt > 0.0) {
    if (iOk) soc_.integrate(I, dt);
    EnergySample e;
    e.dt_s = dt;
    e.volts = V;
    e.amps = I;
    e.voltsOk = vOk;
    e.ampsOk = iOk;
    e.alternatorOn = finite(measuredAltAmps) && measuredAltAmps > p_.CurrentThreshold;
    e.altAmps = measuredAltAmps;
    e.solarW = usable(in.solarPowerW, in.now, battery_k::SOLAR_STALE_MS) ? in.solarPowerW.value : kNoValue;
    energy_.integrate(e);
    averages_.integrate(dt, V, vOk);
  }

  if (in.now - lastSocUpdate_ >= fromMs(p_.SOCUpdateInterval)) {
    const double elapsed = toSec(in.now - lastSocUpdate_);
    lastSocUpdate_ = in.now;
    closeSocInterval(in.now, elapsed, ev);
  }
  trackRest(in, dt, iOk ? I : NAN, vOk ? V : NAN, measuredAltAmps);
  if (in.now - lastChargeTimes_ >= fromMs(k::INA_SLOW_INTERVAL_MS)) {
    lastChargeTimes_ = in.now;
    telemetryStale_ = true;
    soc_.predict(getBatteryCurrent(in), p_.BatteryCapacity_Ah);
  }
}

// One SoC interval: the count, the points of known SoC in step with it, the
// energies, the bank class, the averages, then the full-charge detector
// (which may reset the count the averages have just weighed).
void BatteryMonitor::closeSocInterval(TimeNs now, double elapsed_s, EventBatch& ev) noexcept {
  telemetryStale_ = true;
  const double cap = p_.BatteryCapacity_Ah;

  health_.addAh(soc_.commit(elapsed_s, p_), elapsed_s);
  const double restedPct = rest_.takeRestedPoint();
  if (finite(restedPct)) {
    capacityPoint(now, restedPct, false, ev);
    // Until a full charge has set the count, a 4 h rested voltage is a far
    // better SoC than the first-start estimate (30 s of rest) it replaces
    // (docs/batteries.md "State of charge at first start").
    if (socSource() != SocSource::Counted) soc_.setPercent(restedPct, cap, SocSource::OcvEstimate);
  }
  if (finite(health_.bmsSocPct())) capacityPoint(now, health_.bmsSocPct(), false, ev);

  energy_.commit();
  if (lastValidVoltage_ > 4.0)
    nominalVoltage_ =
        nominalVoltage(bankClassOfVoltage(lastValidVoltage_));  // docs/deviations.md "One bank-class rule"
  averages_.commit(socPercent());

  FullChargeInput f;
  f.elapsed_s = elapsed_s;
  f.live = socInputsValid_;
  f.amps = batteryCurrentForSoC_;
  f.volts = lastValidVoltage_;
  if (soc_.fullChargeDue(f, p_)) declareFullCharge(now, ev);
}

void BatteryMonitor::declareFullCharge(TimeNs now, EventBatch& ev) noexcept {
  const double cap = p_.BatteryCapacity_Ah;
  if (!soc_.fullDetected())
    ev.push(makeEvent(now, EventLevel::Info, EventCode::FullChargeDetected, soc_.countAh(), cap));
  // The gain correction compares the count at "full" before it is reset.
  GainCorrectionInput g;
  g.now = now;
  g.enabled = p_.AutoShuntGainCorrection;
  g.referenceValid = soc_.referenceValid();
  g.countSinceReference_Ah = soc_.sinceReferenceAh();
  g.expectedCapacity_Ah = cap;
  gain_.atFullCharge(g, ev);
  capacityPoint(now, 100.0, true, ev);
  soc_.markFull(cap);
  telemetryStale_ = true;
}

void BatteryMonitor::chargeCompletedOnTail(TimeNs now, EventBatch& ev) noexcept {
  // Only on live samples, as the detector: the tail was measured.
  if (socInputsValid_) declareFullCharge(now, ev);
}

void BatteryMonitor::capacityPoint(TimeNs now, double socPct, bool full, EventBatch& ev) noexcept {
  if (health_.knownSoc(now, socPct, full, p_.BatteryCapacity_Ah, ev)) telemetryStale_ = true;
}

// After the SoC interval: the first-start estimate, the resistance and the
// BMS's SoC, then the rested-voltage point (it uses this tick's resistance).
void BatteryMonitor::trackRest(const Inputs& in, double dt_s, double amps, double volts,
                               double altAmps) noexcept {
  RestInput r;
  r.dt_s = dt_s;
  r.amps = amps;
  r.volts = volts;
  r.altAmps = altAmps;
  r.nominalVoltage = nominalVoltage_;
  const double startPct = rest_.firstStartEstimate(r, socSource() == SocSource::Unknown, p_);
  if (finite(startPct)) {
    soc_.setPercent(startPct, p_.BatteryCapacity_Ah, SocSource::OcvEstimate);
    telemetryStale_ = true;
  }
  // The battery temperature counts while the temperature rules count it (BATTERY_TEMP_STALE_MS).
  r.tempC = fresh::batteryTemp(in.batteryTempC, in.now) ? in.batteryTempC.value : kNoValue;
  HealthInput h;
  h.dt_s = dt_s;
  h.amps = amps;
  h.volts = volts;
  h.tempC = r.tempC;
  h.capacityAh = p_.BatteryCapacity_Ah;
  const bool bmsFresh =
      std::isfinite(in.bms.socPct) && in.bms.stamp != 0 && fresh::bms(in.bms.stamp, in.now, p_.BmsStaleS);
  h.bmsSocPct = bmsFresh ? in.bms.socPct : kNoValue;
  if (health_.update(h)) telemetryStale_ = true;
  rest_.trackRestedPoint(r, p_, health_.resistance());
}

}  // namespace xr
