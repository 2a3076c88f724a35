// SocCounter (docs/batteries.md "State of charge", "Full-charge detection").
#include "battery/soc_counter.h"

#include <algorithm>
#include <cmath>

#include "battery/monitor_helpers.h"
#include "params/constants.h"
#include "params/derived.h"

namespace xr {

using namespace battery_detail;

SocCounter::SocCounter(double capacityAh) noexcept
    // Assume full: with SOC gating (charging_stage rebulkDue) a low guess would
    // force re-bulk "regardless of voltage" until the first full charge, i.e.
    // the charger would never rest; a full guess defers to voltage/current
    // re-bulk once 5 % has been counted out. source() says it is a guess.
    : count_Ah_(capacityAh * kUnknownSocPercent / 100.0) {}

double SocCounter::peukertFactor(double dischargeCurrent_A, double capacity_Ah, double ratedCurrent_A,
                                 double exponent) noexcept {
  const double peukertThreshold = capacity_Ah / 100.0;  // C/100
  if (!(dischargeCurrent_A > peukertThreshold) || !(ratedCurrent_A > 0.0)) return 1.0;
  const double currentRatio = ratedCurrent_A / dischargeCurrent_A;
  const double f = std::pow(currentRatio, exponent - 1.0);
  return clampFinite(f, k::PEUKERT_FACTOR_MIN, k::PEUKERT_FACTOR_MAX, 1.0);
}

// Coulomb counting: the interval's amp-hours, charge efficiency in, Peukert
// out, committed in whole hundredths (nothing tiny is lost).
double SocCounter::commit(double elapsed_s, const Params& p) noexcept {
  const double cap = p.BatteryCapacity_Ah;
  const double deltaAh = intervalAh_;
  intervalAh_ = 0.0;
  double batteryDeltaAh = 0.0;
  if (deltaAh > 0.0) {
    batteryDeltaAh = deltaAh * (p.ChargeEfficiency / 100.0);
  } else if (deltaAh < 0.0) {
    const double dischargeCurrent_A = elapsed_s > 0.0 ? -deltaAh * 3600.0 / elapsed_s : 0.0;
    // Cp = C20 (I20/I)^(n-1) is the effective capacity at I; removing
    // deltaAh / (Cp/C20) Ah depletes a bank faster at high currents.
    batteryDeltaAh =
        deltaAh / peukertFactor(dischargeCurrent_A, cap, p.PeukertRatedCurrent_A, p.PeukertExponent);
  }
  remainder_Ah_ += batteryDeltaAh;
  if (referenceValid_) sinceReference_Ah_ += batteryDeltaAh;
  if (std::fabs(remainder_Ah_) >= battery_k::COULOMB_COMMIT_AH) {
    // Commit whole hundredths, retain the remainder (never lose tiny amounts).
    const double steps = std::trunc(remainder_Ah_ / battery_k::COULOMB_COMMIT_AH);
    const double committed = steps * battery_k::COULOMB_COMMIT_AH;
    count_Ah_ += committed;
    remainder_Ah_ -= committed;
  }
  count_Ah_ = std::clamp(count_Ah_, 0.0, cap);
  return batteryDeltaAh;
}

bool SocCounter::fullChargeDue(const FullChargeInput& in, const Params& p) noexcept {
  const double tail_A = p.TailCurrent * p.BatteryCapacity_Ah / 100.0;
  // Only on live samples: a dead INA228 reads "0 A" and must not declare the
  // bank full at the last voltage it saw.
  if (in.live && std::fabs(in.amps) <= tail_A && in.volts >= chargedVoltageV(p)) {
    fullTimer_s_ += in.elapsed_s;
    return fullTimer_s_ >= p.ChargedDetectionTime;
  }
  fullTimer_s_ = 0.0;
  fullDetected_ = false;
  return false;
}

void SocCounter::markFull(double capacityAh) noexcept {
  count_Ah_ = capacityAh;
  remainder_Ah_ = 0.0;
  fullDetected_ = true;
  source_ = SocSource::Counted;
  referenceValid_ = true;
  sinceReference_Ah_ = capacityAh;
}

void SocCounter::setPercent(double pct, double capacityAh, SocSource source) noexcept {
  count_Ah_ = capacityAh * pct / 100.0;
  remainder_Ah_ = 0.0;
  source_ = source;
}

void SocCounter::setByOperator(double pct, double capacityAh) noexcept {
  count_Ah_ = capacityAh * pct / 100.0;
  remainder_Ah_ = 0.0;
  // The operator's figure is a reference point for the gain correction.
  referenceValid_ = true;
  sinceReference_Ah_ = count_Ah_;
  source_ = SocSource::Counted;
}

void SocCounter::clampTo(double capacityAh) noexcept { count_Ah_ = std::clamp(count_Ah_, 0.0, capacityAh); }

void SocCounter::predict(double amps, double capacityAh) noexcept {
  const double soc = percent(capacityAh);
  timeToFullMin_ = k::PREDICTION_NA;
  timeToEmptyMin_ = k::PREDICTION_NA;
  if (!finite(amps)) return;
  if (amps > 0.01) {
    const double remainingCapacity_Ah = capacityAh * (100.0 - soc) / 100.0;
    timeToFullMin_ = remainingCapacity_Ah / amps * 60.0;
  } else if (amps < -0.01) {
    const double availableCapacity_Ah = capacityAh * soc / 100.0;
    timeToEmptyMin_ = availableCapacity_Ah / (-amps) * 60.0;
  }
}

void SocCounter::toLedger(BatteryLedger& l) const noexcept {
  l.CoulombCount_Ah = count_Ah_;
  l.coulombAccumulator_Ah = remainder_Ah_;
  l.SocSource = static_cast<double>(static_cast<int>(source_));
}

void SocCounter::restore(const BatteryLedger& l, double capacityAh) noexcept {
  const double cap = capacityAh;
  const bool countOk = std::isfinite(l.CoulombCount_Ah) && l.valid;
  count_Ah_ = clampFinite(l.CoulombCount_Ah, 0.0, cap, cap * kUnknownSocPercent / 100.0);
  // 0, 1 or 2; anything else (a damaged row) is counted as unknown.
  const double src = l.SocSource;
  source_ = countOk && (src == 1.0 || src == 2.0) ? static_cast<SocSource>(static_cast<int>(src))
                                                  : SocSource::Unknown;
  remainder_Ah_ =
      clampFinite(l.coulombAccumulator_Ah, -battery_k::COULOMB_COMMIT_AH, battery_k::COULOMB_COMMIT_AH, 0.0);
  referenceValid_ = false;
}

}  // namespace xr
