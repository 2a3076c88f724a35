// BatteryMonitor: state of charge, Peukert, energy counters, shunt gain
// correction and charge times (docs/batteries.md).
#include <algorithm>
#include <cmath>

#include "battery/battery_monitor.h"
#include "battery/monitor_helpers.h"
#include "params/constants.h"
#include "params/derived.h"

namespace xr {

using namespace battery_detail;

// ---------------------------------------------------------------- SoC

double BatteryMonitor::peukertFactor(double dischargeCurrent_A, double capacity_Ah, double ratedCurrent_A,
                                     double exponent) noexcept {
  const double peukertThreshold = capacity_Ah / 100.0;  // C/100
  if (!(dischargeCurrent_A > peukertThreshold) || !(ratedCurrent_A > 0.0)) return 1.0;
  const double currentRatio = ratedCurrent_A / dischargeCurrent_A;
  const double f = std::pow(currentRatio, exponent - 1.0);
  return clampFinite(f, k::PEUKERT_FACTOR_MIN, k::PEUKERT_FACTOR_MAX, 1.0);
}

void BatteryMonitor::updateBatterySoc(const Inputs& in, double measuredAltAmps, EventBatch& ev) noexcept {
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
  estimateSocAtRest(dt, iOk ? I : NAN, vOk ? V : NAN, measuredAltAmps);
  trackHealth(in, dt, iOk ? I : NAN, vOk ? V : NAN, measuredAltAmps);
  if (in.now - lastChargeTimes_ >= fromMs(k::INA_SLOW_INTERVAL_MS)) {
    lastChargeTimes_ = in.now;
    calculateChargeTimes(in);
  }
}

void BatteryMonitor::commitEnergy(Energy& e, double& lifetimeWhole, double delta_Wh) noexcept {
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

// Coulomb counting: the interval's amp-hours, charge efficiency in, Peukert
// out, committed in whole hundredths (nothing tiny is lost).
void BatteryMonitor::countCoulombs(double elapsed_s) noexcept {
  const double cap = p_.BatteryCapacity_Ah;
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
  capacity_.addAh(batteryDeltaAh, elapsed_s);
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
}

// Fuel (alternator only; the seed's 30 % x 50 % chain).
void BatteryMonitor::countFuel() noexcept {
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
}

void BatteryMonitor::runSocBody(TimeNs now, double elapsed_s, EventBatch& ev) noexcept {
  telemetryStale_ = true;
  const double cap = p_.BatteryCapacity_Ah;

  countCoulombs(elapsed_s);
  // Points of known SoC for the measured capacity, in step with the count.
  if (finite(pendingRestSocPct_)) {
    capacityPoint(now, pendingRestSocPct_, false, ev);
    // Until a full charge has set the count, a 4 h rested voltage is a far
    // better SoC than the first-start estimate (30 s of rest) it replaces
    // (docs/batteries.md "State of charge at first start").
    if (socSource() != SocSource::Counted) {
      ledger_.CoulombCount_Ah = cap * pendingRestSocPct_ / 100.0;
      ledger_.coulombAccumulator_Ah = 0.0;
      setSocSource(SocSource::OcvEstimate);
    }
  }
  pendingRestSocPct_ = kNoValue;
  if (finite(bmsSocPct_)) capacityPoint(now, bmsSocPct_, false, ev);

  // ---- energy
  commitEnergy(charged_, ledger_.ChargedEnergy_AllTime_Wh, intChargeWh_);
  commitEnergy(discharged_, ledger_.DischargedEnergy_AllTime_Wh, intDischargeWh_);
  commitEnergy(altCharged_, ledger_.AlternatorChargedEnergy_AllTime_Wh, intAltWh_);
  commitEnergy(solar_, ledger_.SolarChargedEnergy_AllTime_Wh, intSolarWh_);
  AlternatorOnTime_s_ += intAltOn_s_;
  ledger_.AlternatorOnTime_AllTime_s += intAltOn_s_;

  countFuel();

  // ---- system class and cycles
  if (lastValidVoltage_ > 4.0)
    nominalVoltage_ =
        nominalVoltage(bankClassOfVoltage(lastValidVoltage_));  // docs/deviations.md "One bank-class rule"

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
      currentBatteryVoltage_ >= chargedVoltageV(p_)) {
    FullChargeTimer_s_ += elapsed_s;
    if (FullChargeTimer_s_ >= p_.ChargedDetectionTime) declareFullCharge(now, ev);
  } else {
    FullChargeTimer_s_ = 0.0;
    FullChargeDetected_ = false;
  }

  intAh_ = intChargeWh_ = intDischargeWh_ = intAltWh_ = intSolarWh_ = 0.0;
  intAltOn_s_ = intSoc_s_ = intV_s_ = intVtime_s_ = 0.0;
}

void BatteryMonitor::declareFullCharge(TimeNs now, EventBatch& ev) noexcept {
  const double cap = p_.BatteryCapacity_Ah;
  if (!FullChargeDetected_)
    ev.push(makeEvent(now, EventLevel::Info, EventCode::FullChargeDetected, ledger_.CoulombCount_Ah, cap));
  // Gain correction compares the count at "full" before it is reset.
  if (p_.AutoShuntGainCorrection)
    applySocGainCorrection(now, ev);
  else
    lastGainGuard_ = GainGuard::FeatureOff;
  capacityPoint(now, 100.0, true, ev);
  ledger_.CoulombCount_Ah = cap;
  ledger_.coulombAccumulator_Ah = 0.0;
  FullChargeDetected_ = true;
  setSocSource(SocSource::Counted);
  gainReferenceValid_ = true;
  unclampedCount_Ah_ = cap;
  telemetryStale_ = true;
}

void BatteryMonitor::chargeCompletedOnTail(TimeNs now, EventBatch& ev) noexcept {
  // Only on live samples, as the detector above: the tail was measured.
  if (socInputsValid_) declareFullCharge(now, ev);
}

void BatteryMonitor::applySocGainCorrection(TimeNs now, EventBatch& ev) noexcept {
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

void BatteryMonitor::calculateChargeTimes(const Inputs& in) noexcept {
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

}  // namespace xr
