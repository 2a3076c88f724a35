// BatteryMonitor — seeds/battery-management.md. See battery_monitor.h for the
// call order Regulator::step follows.
#include "battery/battery_monitor.h"

#include <algorithm>
#include <cmath>

#include "core/finite.h"
#include "params/constants.h"

namespace xr {

namespace {

// A reading usable at `now`: has a value and is no older than maxAgeMs.
bool usable(const Reading& r, TimeNs now, std::int64_t maxAgeMs) {
  return finite(r.value) && r.stamp != 0 && now - r.stamp <= fromMs(maxAgeMs);
}

double clampFinite(double v, double lo, double hi, double fallback) {
  if (!finite(v)) return fallback;
  return std::clamp(v, lo, hi);
}

// Battery events carry no protection reason.
Event makeEvent(TimeNs t, EventLevel level, EventCode code, double a = 0.0, double b = 0.0, int detail = 0) {
  return xr::makeEvent(t, level, code, Reason::NONE, a, b, detail);
}

}  // namespace

BatteryMonitor::BatteryMonitor(const Params& p) : p_(p) {
  // A fresh ledger (first start, nothing restored) does not know the SoC.
  // Assume full: with SOC gating (charging_stage rebulkDue) a low guess would
  // force re-bulk "regardless of voltage" until the first full charge, i.e.
  // the charger would never rest; a full guess defers to voltage/current
  // re-bulk once 5 % has been counted out. socKnown() says it is a guess.
  ledger_.CoulombCount_Ah = p_.BatteryCapacity_Ah * kUnknownSocPercent / 100.0;
  ledger_.valid = true;
}

void BatteryMonitor::setParams(const Params& p) {
  p_ = p;
  telemetryStale_ = true;
  ledger_.CoulombCount_Ah = std::clamp(ledger_.CoulombCount_Ah, 0.0, p_.BatteryCapacity_Ah);
}

// ---------------------------------------------------------------- sources of truth

double BatteryMonitor::getBatteryVoltage(const Inputs& in) const { return in.IBV.value; }

bool BatteryMonitor::usingVictronCurrent(const Inputs& in) const {
  return p_.BatteryCurrentSource == 3 && usable(in.VictronCurrent, in.now, k::VICTRON_STALE_MS);
}

double BatteryMonitor::getBatteryCurrent(const Inputs& in) const {
  if (usingVictronCurrent(in)) return in.VictronCurrent.value;
  return correctedBcur(in.Bcur.value);
}

// ---------------------------------------------------------------- auto-zero

double BatteryMonitor::temperatureF(const Inputs& in) const {
  return p_.TempSource == 1 ? in.thermistorF.value : in.AlternatorTemperatureF.value;
}

void BatteryMonitor::checkAutoZeroTriggers(const Inputs& in, EventBatch& ev) {
  const double temp = temperatureF(in);
  if (!started_) {
    started_ = true;
    lastTick_ = in.now;
    lastSocUpdate_ = in.now;
    lastChargeTimes_ = in.now;
    lastAutoZeroTime_ = in.now;  // hourly timer starts at the first tick
  }
  if (!haveAutoZeroTemp_ && finite(temp)) {
    haveAutoZeroTemp_ = true;
    lastAutoZeroTemp_ = temp;
  }
  if (!p_.AutoAltCurrentZero || autoZeroActive_) return;
  const double rpm = in.rpm.value;
  if (!finite(rpm) || rpm < k::AUTO_ZERO_MIN_RPM) return;
  const bool intervalDue = in.now - lastAutoZeroTime_ >= fromMs(k::AUTO_ZERO_INTERVAL);
  const bool tempShift =
      haveAutoZeroTemp_ && finite(temp) && std::fabs(temp - lastAutoZeroTemp_) >= k::AUTO_ZERO_TEMP_DELTA;
  if (!intervalDue && !tempShift) return;
  autoZeroActive_ = true;
  telemetryStale_ = true;
  autoZeroStartTime_ = in.now;
  autoZeroAccumulator_ = 0.0;
  autoZeroSampleCount_ = 0;
  ev.push(makeEvent(in.now, EventLevel::Info, EventCode::AutoZeroStarted, ledger_.DynamicAltCurrentZero, 0.0,
                    tempShift ? 1 : 0));
}

bool BatteryMonitor::processActiveAutoZero(const Inputs& in, EventBatch& ev) {
  const TimeNs elapsed = in.now - autoZeroStartTime_;
  if (elapsed < fromMs(battery_k::AUTO_ZERO_DURATION_MS)) {
    // Field is held off by the caller; sample only after the 2 s settle and
    // only new CH1 conversions (the same sample must not count twice).
    if (elapsed > fromMs(k::AUTO_ZERO_SETTLE_MS) && in.altCurrentRaw.fresh &&
        finite(in.altCurrentRaw.value)) {
      autoZeroAccumulator_ += in.altCurrentRaw.value;
      ++autoZeroSampleCount_;
    }
    return true;
  }
  int detail = 0;
  double zero = ledger_.DynamicAltCurrentZero;
  if (autoZeroSampleCount_ == 0) {
    detail = 1;  // no samples: keep the old zero
  } else {
    const double mean = autoZeroAccumulator_ / static_cast<double>(autoZeroSampleCount_);
    if (std::fabs(mean) > battery_k::AUTO_ZERO_MAX_OFFSET_A)
      detail = 2;
    else
      zero = mean;
  }
  ledger_.DynamicAltCurrentZero = zero;
  telemetryStale_ = true;
  lastAutoZeroTime_ = in.now;
  const double temp = temperatureF(in);
  if (finite(temp)) {
    lastAutoZeroTemp_ = temp;
    haveAutoZeroTemp_ = true;
  }
  autoZeroActive_ = false;
  autoZeroStartTime_ = 0;
  ev.push(makeEvent(in.now, detail == 0 ? EventLevel::Info : EventLevel::Warning, EventCode::AutoZeroDone,
                    zero, static_cast<double>(autoZeroSampleCount_), detail));
  return false;
}

// ---------------------------------------------------------------- SoC

double BatteryMonitor::peukertFactor(double dischargeCurrent_A, double capacity_Ah, double ratedCurrent_A,
                                     double exponent) {
  const double peukertThreshold = capacity_Ah / 100.0;  // C/100
  if (!(dischargeCurrent_A > peukertThreshold) || !(ratedCurrent_A > 0.0)) return 1.0;
  const double currentRatio = ratedCurrent_A / dischargeCurrent_A;
  const double f = std::pow(currentRatio, exponent - 1.0);
  return clampFinite(f, k::PEUKERT_FACTOR_MIN, k::PEUKERT_FACTOR_MAX, 1.0);
}

void BatteryMonitor::UpdateBatterySOC(const Inputs& in, double measuredAltAmps, EventBatch& ev) {
  if (!started_) {
    started_ = true;
    lastTick_ = in.now;
    lastSocUpdate_ = in.now;
    lastChargeTimes_ = in.now;
    lastAutoZeroTime_ = in.now;
  }
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
  if (vOk) {
    currentBatteryVoltage_ = V;
    lastValidVoltage_ = V;
  }
  batteryCurrentForSoC_ = iOk ? I : 0.0;
  socInputsValid_ = iOk && vOk;
  usingVictron_ = victron;

  if (dt > 0.0) {
    if (iOk) intAh_ += I * dt / 3600.0;
    if (iOk && vOk) {
      const double wh = V * I * dt / 3600.0;
      if (wh > 0.0)
        intChargeWh_ += wh;
      else
        intDischargeWh_ -= wh;
    }
    const bool alternatorIsOn = finite(measuredAltAmps) && measuredAltAmps > p_.CurrentThreshold;
    if (alternatorIsOn) {
      intAltOn_s_ += dt;
      if (vOk) intAltWh_ += V * measuredAltAmps * dt / 3600.0;
    }
    if (usable(in.solarPowerW, in.now, battery_k::SOLAR_STALE_MS) && in.solarPowerW.value > 0.0)
      intSolarWh_ += in.solarPowerW.value * dt / 3600.0;
    if (vOk) {
      intV_s_ += V * dt;
      intVtime_s_ += dt;
    }
    intSoc_s_ += dt;
  }

  if (in.now - lastSocUpdate_ >= fromMs(p_.SOCUpdateInterval)) {
    const double elapsed = toSec(in.now - lastSocUpdate_);
    lastSocUpdate_ = in.now;
    runSocBody(in.now, elapsed, ev);
  }
  if (in.now - lastChargeTimes_ >= fromMs(k::INA_SLOW_INTERVAL_MS)) {
    lastChargeTimes_ = in.now;
    calculateChargeTimes(in);
  }
}

void BatteryMonitor::commitEnergy(Energy& e, double& lifetimeWhole, double delta_Wh) {
  if (!(delta_Wh > 0.0)) return;
  e.session_Wh += delta_Wh;
  // Float-fraction-retained pattern of the seed: the lifetime total is kept
  // as whole Wh plus a small fraction, so a 50 mW draw is never rounded away
  // against a lifetime of megawatt-hours.
  e.lifetimeFraction_Wh += delta_Wh;
  if (e.lifetimeFraction_Wh >= 1.0) {
    const double whole = std::floor(e.lifetimeFraction_Wh);
    lifetimeWhole += whole;
    e.lifetimeFraction_Wh -= whole;
  }
}

void BatteryMonitor::runSocBody(TimeNs now, double elapsed_s, EventBatch& ev) {
  telemetryStale_ = true;
  const double cap = p_.BatteryCapacity_Ah;

  // ---- coulomb counting
  const double deltaAh = intAh_;
  double batteryDeltaAh = 0.0;
  if (deltaAh > 0.0) {
    batteryDeltaAh = deltaAh * (p_.ChargeEfficiency / 100.0);
  } else if (deltaAh < 0.0) {
    const double dischargeCurrent_A = elapsed_s > 0.0 ? -deltaAh * 3600.0 / elapsed_s : 0.0;
    // Cp = C20 (I20/I)^(n-1) is the effective capacity at I; removing
    // deltaAh / (Cp/C20) Ah depletes a bank faster at high currents, as
    // the seed says ("Peukert reduces effective capacity").
    batteryDeltaAh =
        deltaAh / peukertFactor(dischargeCurrent_A, cap, p_.PeukertRatedCurrent_A, p_.PeukertExponent);
  }
  ledger_.coulombAccumulator_Ah += batteryDeltaAh;
  if (gainReferenceValid_) unclampedCount_Ah_ += batteryDeltaAh;
  if (std::fabs(ledger_.coulombAccumulator_Ah) >= battery_k::COULOMB_COMMIT_AH) {
    // Commit whole hundredths, retain the remainder (never lose tiny amounts).
    const double steps = std::trunc(ledger_.coulombAccumulator_Ah / battery_k::COULOMB_COMMIT_AH);
    const double committed = steps * battery_k::COULOMB_COMMIT_AH;
    ledger_.CoulombCount_Ah += committed;
    ledger_.coulombAccumulator_Ah -= committed;
  }
  ledger_.CoulombCount_Ah = std::clamp(ledger_.CoulombCount_Ah, 0.0, cap);

  // ---- energy
  commitEnergy(charged_, ledger_.ChargedEnergy_AllTime_Wh, intChargeWh_);
  commitEnergy(discharged_, ledger_.DischargedEnergy_AllTime_Wh, intDischargeWh_);
  commitEnergy(altCharged_, ledger_.AlternatorChargedEnergy_AllTime_Wh, intAltWh_);
  commitEnergy(solar_, ledger_.SolarChargedEnergy_AllTime_Wh, intSolarWh_);
  AlternatorOnTime_s_ += intAltOn_s_;
  ledger_.AlternatorOnTime_AllTime_s += intAltOn_s_;

  // ---- fuel (alternator only; the seed's 30 % x 50 % chain)
  if (intAltWh_ > 0.0) {
    const double energyJoules = intAltWh_ * 3600.0;
    const double fuelEnergyUsed_J =
        energyJoules / (k::FUEL_ENGINE_EFFICIENCY * k::FUEL_ALTERNATOR_EFFICIENCY);
    const double fuelUsed_L = fuelEnergyUsed_J / k::DIESEL_J_PER_ML / 1000.0;
    fuelFraction_L_ += fuelUsed_L;
    // Roll whole hundredths of a litre, keep the rest (seed).
    const double hundredths = std::floor(fuelFraction_L_ * 100.0) / 100.0;
    if (hundredths > 0.0) {
      AlternatorFuelUsed_L_ += hundredths;
      ledger_.AlternatorFuelUsed_AllTime_L += hundredths;
      fuelFraction_L_ -= hundredths;
    }
  }

  // ---- system class and cycles
  if (lastValidVoltage_ > 4.0)
    nominalVoltage_ = lastValidVoltage_ < 16.0 ? 12 : (lastValidVoltage_ < 32.0 ? 24 : 48);

  // ---- time-weighted averages
  const double soc = socPercent();
  socAccumulator_ += soc * intSoc_s_;
  totalSocSampleTime_ += intSoc_s_;
  ledger_.socAccumulator_AllTime += soc * intSoc_s_;
  ledger_.totalSocSampleTime_AllTime += intSoc_s_;
  ledger_.voltageAccumulator_AllTime += intV_s_;
  ledger_.totalVoltageSampleTime_AllTime += intVtime_s_;

  // ---- full-charge detection (independent of the charging stage)
  const double tail_A = p_.TailCurrent * cap / 100.0;
  // Only on live samples: a dead INA228 reads "0 A" and must not declare the
  // bank full at the last voltage it saw.
  if (socInputsValid_ && std::fabs(batteryCurrentForSoC_) <= tail_A &&
      currentBatteryVoltage_ >= p_.ChargedVoltage) {
    FullChargeTimer_s_ += elapsed_s;
    if (FullChargeTimer_s_ >= p_.ChargedDetectionTime) {
      if (!FullChargeDetected_)
        ev.push(
            makeEvent(now, EventLevel::Info, EventCode::FullChargeDetected, ledger_.CoulombCount_Ah, cap));
      // Gain correction compares the count at "full" before it is reset.
      if (p_.AutoShuntGainCorrection)
        applySocGainCorrection(now, ev);
      else
        lastGainGuard_ = GainGuard::FeatureOff;
      ledger_.CoulombCount_Ah = cap;
      ledger_.coulombAccumulator_Ah = 0.0;
      FullChargeDetected_ = true;
      socKnown_ = true;
      gainReferenceValid_ = true;
      unclampedCount_Ah_ = cap;
    }
  } else {
    FullChargeTimer_s_ = 0.0;
    FullChargeDetected_ = false;
  }

  intAh_ = intChargeWh_ = intDischargeWh_ = intAltWh_ = intSolarWh_ = 0.0;
  intAltOn_s_ = intSoc_s_ = intV_s_ = intVtime_s_ = 0.0;
}

void BatteryMonitor::applySocGainCorrection(TimeNs now, EventBatch& ev) {
  using namespace battery_k;
  if (!p_.AutoShuntGainCorrection) {
    lastGainGuard_ = GainGuard::FeatureOff;
    return;
  }
  if (haveGainCorrection_ && now - lastGainCorrectionTime_ < fromMs(MIN_GAIN_CORRECTION_INTERVAL_MS)) {
    lastGainGuard_ = GainGuard::TooSoon;
    return;
  }
  if (!gainReferenceValid_) {
    lastGainGuard_ = GainGuard::NoReference;
    return;
  }
  const double calculatedCapacity = unclampedCount_Ah_;
  const double expectedCapacity = p_.BatteryCapacity_Ah;
  if (!finite(calculatedCapacity) || calculatedCapacity < MIN_PLAUSIBLE_CAPACITY_AH ||
      expectedCapacity < MIN_PLAUSIBLE_CAPACITY_AH) {
    lastGainGuard_ = GainGuard::ImplausibleCapacity;
    return;
  }
  const double errorRatio = std::fabs(expectedCapacity - calculatedCapacity) / expectedCapacity;
  if (errorRatio > MAX_REASONABLE_ERROR) {
    lastGainGuard_ = GainGuard::ErrorTooLarge;
    ev.push(makeEvent(now, EventLevel::Warning, EventCode::ShuntGainCorrected, ledger_.DynamicShuntGainFactor,
                      errorRatio, static_cast<int>(GainGuard::ErrorTooLarge)));
    return;
  }
  const double currentFactor = ledger_.DynamicShuntGainFactor;
  const double desiredCorrectionFactor = expectedCapacity / calculatedCapacity;
  double newFactor = currentFactor * desiredCorrectionFactor;
  const double maxChange = currentFactor * MAX_GAIN_ADJUSTMENT_PER_CYCLE;
  newFactor = std::clamp(newFactor, currentFactor - maxChange, currentFactor + maxChange);
  newFactor = std::clamp(newFactor, MIN_DYNAMIC_GAIN_FACTOR, MAX_DYNAMIC_GAIN_FACTOR);
  ledger_.DynamicShuntGainFactor = newFactor;
  haveGainCorrection_ = true;
  lastGainCorrectionTime_ = now;
  lastGainGuard_ = GainGuard::Applied;
  ev.push(makeEvent(now, EventLevel::Info, EventCode::ShuntGainCorrected, newFactor, currentFactor, 0));
}

void BatteryMonitor::calculateChargeTimes(const Inputs& in) {
  telemetryStale_ = true;
  const double currentAmps = getBatteryCurrent(in);
  const double currentSoC = socPercent();
  const double cap = p_.BatteryCapacity_Ah;
  timeToFullChargeMin_ = k::PREDICTION_NA;
  timeToFullDischargeMin_ = k::PREDICTION_NA;
  if (!finite(currentAmps)) return;
  if (currentAmps > 0.01) {
    const double remainingCapacity_Ah = cap * (100.0 - currentSoC) / 100.0;
    timeToFullChargeMin_ = remainingCapacity_Ah / currentAmps * 60.0;
  } else if (currentAmps < -0.01) {
    const double availableCapacity_Ah = cap * currentSoC / 100.0;
    timeToFullDischargeMin_ = availableCapacity_Ah / (-currentAmps) * 60.0;
  }
}

// ---------------------------------------------------------------- commands

void BatteryMonitor::resetSocGain() {
  ledger_.DynamicShuntGainFactor = 1.0;
  telemetryStale_ = true;
}

void BatteryMonitor::resetAltZero() {
  ledger_.DynamicAltCurrentZero = 0.0;
  telemetryStale_ = true;
}

bool BatteryMonitor::setSoc(double pct) {
  if (!finite(pct) || pct < 0.0 || pct > 100.0) return false;
  ledger_.CoulombCount_Ah = p_.BatteryCapacity_Ah * pct / 100.0;
  ledger_.coulombAccumulator_Ah = 0.0;
  telemetryStale_ = true;
  // The operator's figure is a reference point for the gain correction.
  gainReferenceValid_ = true;
  unclampedCount_Ah_ = ledger_.CoulombCount_Ah;
  socKnown_ = true;
  return true;
}

// ---------------------------------------------------------------- persistence

BatteryLedger BatteryMonitor::ledger() const {
  BatteryLedger l = ledger_;
  // Whole + retained fraction: the store keeps the exact total.
  l.ChargedEnergy_AllTime_Wh += charged_.lifetimeFraction_Wh;
  l.DischargedEnergy_AllTime_Wh += discharged_.lifetimeFraction_Wh;
  l.AlternatorChargedEnergy_AllTime_Wh += altCharged_.lifetimeFraction_Wh;
  l.SolarChargedEnergy_AllTime_Wh += solar_.lifetimeFraction_Wh;
  l.valid = true;
  return l;
}

void BatteryMonitor::restoreLedger(const BatteryLedger& in) {
  using namespace battery_k;
  BatteryLedger l = in;
  const double cap = p_.BatteryCapacity_Ah;
  l.CoulombCount_Ah = clampFinite(l.CoulombCount_Ah, 0.0, cap, cap * kUnknownSocPercent / 100.0);
  l.coulombAccumulator_Ah = clampFinite(l.coulombAccumulator_Ah, -COULOMB_COMMIT_AH, COULOMB_COMMIT_AH, 0.0);
  l.DynamicShuntGainFactor =
      clampFinite(l.DynamicShuntGainFactor, MIN_DYNAMIC_GAIN_FACTOR, MAX_DYNAMIC_GAIN_FACTOR, 1.0);
  l.DynamicAltCurrentZero =
      clampFinite(l.DynamicAltCurrentZero, -AUTO_ZERO_MAX_OFFSET_A, AUTO_ZERO_MAX_OFFSET_A, 0.0);
  const double big = 1e15;
  auto nonNeg = [&](double& v) { v = clampFinite(v, 0.0, big, 0.0); };
  nonNeg(l.ChargedEnergy_AllTime_Wh);
  nonNeg(l.DischargedEnergy_AllTime_Wh);
  nonNeg(l.AlternatorChargedEnergy_AllTime_Wh);
  nonNeg(l.SolarChargedEnergy_AllTime_Wh);
  nonNeg(l.socAccumulator_AllTime);
  nonNeg(l.totalSocSampleTime_AllTime);
  nonNeg(l.voltageAccumulator_AllTime);
  nonNeg(l.totalVoltageSampleTime_AllTime);
  nonNeg(l.AlternatorFuelUsed_AllTime_L);
  nonNeg(l.AlternatorOnTime_AllTime_s);
  // Split lifetime energies back into whole Wh + retained fraction.
  auto split = [](double& whole, Energy& e) {
    const double w = std::floor(whole);
    e.lifetimeFraction_Wh = whole - w;
    whole = w;
  };
  split(l.ChargedEnergy_AllTime_Wh, charged_);
  split(l.DischargedEnergy_AllTime_Wh, discharged_);
  split(l.AlternatorChargedEnergy_AllTime_Wh, altCharged_);
  split(l.SolarChargedEnergy_AllTime_Wh, solar_);
  l.valid = true;
  ledger_ = l;
  telemetryStale_ = true;
  gainReferenceValid_ = false;
  socKnown_ = std::isfinite(in.CoulombCount_Ah) && in.valid;
}

// ---------------------------------------------------------------- outputs

double BatteryMonitor::chargedEnergyLifetimeWh() const {
  return ledger_.ChargedEnergy_AllTime_Wh + charged_.lifetimeFraction_Wh;
}

double BatteryMonitor::alternatorChargedEnergyLifetimeWh() const {
  return ledger_.AlternatorChargedEnergy_AllTime_Wh + altCharged_.lifetimeFraction_Wh;
}

void BatteryMonitor::updateTelemetry(BatteryTelemetry& t) {
  if (telemetryStale_) {
    fillTelemetry(t);
    telemetryStale_ = false;
    return;
  }
  // The two fields UpdateBatterySOC() rewrites on every tick.
  t.batteryCurrentForSoC = batteryCurrentForSoC_;
  t.usingVictronCurrent = usingVictron_;
}

void BatteryMonitor::fillTelemetry(BatteryTelemetry& t) const {
  t.SOC_percent = socPercent();
  t.CoulombCount_Ah = ledger_.CoulombCount_Ah;
  t.batteryCurrentForSoC = batteryCurrentForSoC_;
  t.FullChargeDetected = FullChargeDetected_;
  t.ChargedEnergy_Wh = charged_.session_Wh;
  t.DischargedEnergy_Wh = discharged_.session_Wh;
  t.AlternatorChargedEnergy_Wh = altCharged_.session_Wh;
  t.SolarChargedEnergy_Wh = solar_.session_Wh;
  t.AlternatorOnTime_s = AlternatorOnTime_s_;
  t.AlternatorFuelUsed_L = AlternatorFuelUsed_L_;
  const double capWh = p_.BatteryCapacity_Ah * nominalVoltage_;
  t.ChargeCycles = capWh > 0.0 ? charged_.session_Wh / capWh : 0.0;
  t.ChargeCycles_AllTime = capWh > 0.0 ? chargedEnergyLifetimeWh() / capWh : 0.0;
  t.AvgSOC = totalSocSampleTime_ > 0.0 ? socAccumulator_ / totalSocSampleTime_ : 0.0;
  t.AvgSOC_AllTime = ledger_.totalSocSampleTime_AllTime > 0.0
                         ? ledger_.socAccumulator_AllTime / ledger_.totalSocSampleTime_AllTime
                         : 0.0;
  t.AvgVoltage_AllTime = ledger_.totalVoltageSampleTime_AllTime > 0.0
                             ? ledger_.voltageAccumulator_AllTime / ledger_.totalVoltageSampleTime_AllTime
                             : 0.0;
  t.timeToFullChargeMin = timeToFullChargeMin_;
  t.timeToFullDischargeMin = timeToFullDischargeMin_;
  t.DynamicShuntGainFactor = ledger_.DynamicShuntGainFactor;
  t.DynamicAltCurrentZero = ledger_.DynamicAltCurrentZero;
  t.autoZeroActive = autoZeroActive_;
  t.ChargedEnergy_AllTime_Wh = chargedEnergyLifetimeWh();
  t.DischargedEnergy_AllTime_Wh = ledger_.DischargedEnergy_AllTime_Wh + discharged_.lifetimeFraction_Wh;
  t.AlternatorChargedEnergy_AllTime_Wh = alternatorChargedEnergyLifetimeWh();
  t.SolarChargedEnergy_AllTime_Wh = ledger_.SolarChargedEnergy_AllTime_Wh + solar_.lifetimeFraction_Wh;
  t.AlternatorFuelUsed_AllTime_L = ledger_.AlternatorFuelUsed_AllTime_L;
  t.AlternatorOnTime_AllTime_s = ledger_.AlternatorOnTime_AllTime_s;
  t.nominalVoltage = nominalVoltage_;
  t.usingVictronCurrent = usingVictron_;
}

}  // namespace xr
