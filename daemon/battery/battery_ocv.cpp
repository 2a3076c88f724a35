// OcvReanchor: the SoC of a lead-acid bank from its rested voltage
// (docs/batteries.md "State of charge at first start", "Measured capacity").
#include "battery/battery_ocv.h"

#include <cmath>
#include <iterator>

#include "battery/resistance_estimator.h"

namespace xr {
namespace {

// Rested open-circuit voltage of a 12 V (6-cell) lead-acid bank at ~25 degC:
// Lifeline AGM's table (docs/sources.md P3.3, LL) from 25 % to 100 %; its 0 %
// figure (10.50 V) is a loaded cut-off, not a rest voltage, so 0 % is Libre
// Solar's linear 11.52 V (LSOL, x6).
struct OcvPoint {
  double volts12, socPct;
};
constexpr OcvPoint kLeadAcidOcv[] = {
    {11.52, 0.0}, {11.75, 25.0}, {12.20, 50.0}, {12.55, 75.0}, {12.80, 100.0}};

// "At rest" for the first-start estimate: at most 2 % of the capacity
// flowing (a few amps of house load on a 200 Ah bank move the voltage by
// hundredths), the alternator not charging, for 30 s. A true OCV wants hours
// of rest (docs/sources.md P3.5); the figure is shown as an estimate for that reason.
constexpr double kRestCurrentC = 0.02;
constexpr double kRestSeconds = 30.0;

// A rested voltage is a point of known SoC for lead-acid after this long at
// rest: the slow polarisation decays over hours (docs/sources.md P3.5 asks
// for 6 h or more; after 4 h what is left is ~1 % of SoC for an AGM bank,
// docs/batteries.md). The voltage is the mean of the last hour of it.
constexpr double kPointRestS = 4.0 * 3600.0;
constexpr double kPointAverageS = 3600.0;
// "At rest" for this point is wider than the first-start estimate's: a
// fridge compressor on a boat draws 4 to 6 A while it runs, 2 to 3 % of C,
// and the bank rests only with it. Any second within kPointPeakC
// (discharge) or kPointChargeC (charge) counts, with the alternator off;
// the hour the voltage is averaged over must average within kPointMeanC,
// and what still flows is taken off with the measured resistance
// (docs/batteries.md "Measured capacity").
constexpr double kPointPeakC = 0.05, kPointChargeC = 0.02, kPointMeanC = 0.02;

bool isLeadAcid(const Params& p) {
  // BatteryProfile: 0 lifepo4, 1 agm, 2 flooded, 3 gel, 4 custom.
  return p.BatteryProfile >= 1 && p.BatteryProfile <= 3;
}

double socFromRestVoltage12(double v) {
  if (v <= kLeadAcidOcv[0].volts12) return 0.0;
  for (std::size_t i = 1; i < std::size(kLeadAcidOcv); ++i) {
    const OcvPoint& a = kLeadAcidOcv[i - 1];
    const OcvPoint& b = kLeadAcidOcv[i];
    if (v <= b.volts12) return a.socPct + (v - a.volts12) / (b.volts12 - a.volts12) * (b.socPct - a.socPct);
  }
  return 100.0;
}

}  // namespace

bool OcvReanchor::leadAcidAtRest(double amps, double volts, double altAmps, const Params& p) noexcept {
  const bool alternatorOff = !std::isfinite(altAmps) || altAmps <= p.CurrentThreshold;
  return isLeadAcid(p) && std::isfinite(amps) && std::isfinite(volts) &&
         std::fabs(amps) <= kRestCurrentC * p.BatteryCapacity_Ah && alternatorOff;
}

double OcvReanchor::socFromRestVolts(double volts, const Params& p, int nominalVoltage) noexcept {
  const double cells = p.BatteryCells > 0 ? p.BatteryCells : 6.0 * nominalVoltage / 12.0;
  return socFromRestVoltage12(volts * 6.0 / cells);
}

double OcvReanchor::firstStartEstimate(const RestInput& in, bool socUnknown, const Params& p) noexcept {
  if (!socUnknown || !isLeadAcid(p) || !(in.dt_s > 0.0) ||
      !leadAcidAtRest(in.amps, in.volts, in.altAmps, p)) {
    startRest_s_ = startVolt_s_ = 0.0;
    return kNoValue;
  }
  startRest_s_ += in.dt_s;
  startVolt_s_ += in.volts * in.dt_s;
  if (startRest_s_ < kRestSeconds) return kNoValue;
  const double pct = socFromRestVolts(startVolt_s_ / startRest_s_, p, in.nominalVoltage);
  startRest_s_ = startVolt_s_ = 0.0;
  return pct;
}

void OcvReanchor::trackRestedPoint(const RestInput& in, const Params& p,
                                   const ResistanceEstimator& r) noexcept {
  const double c = p.BatteryCapacity_Ah;
  // leadAcidAtRest with no current: a lead-acid bank, a voltage, the alternator off.
  const bool resting = leadAcidAtRest(0.0, in.volts, in.altAmps, p) && std::isfinite(in.amps) &&
                       in.amps <= kPointChargeC * c && in.amps >= -kPointPeakC * c;
  if (!resting) {
    rest_s_ = restV_s_ = restA_s_ = restAvg_s_ = 0.0;
    restTaken_ = false;
    return;
  }
  if (!(in.dt_s > 0.0) || restTaken_) return;
  rest_s_ += in.dt_s;
  if (rest_s_ > kPointRestS - kPointAverageS) {
    restV_s_ += in.volts * in.dt_s;
    restA_s_ += in.amps * in.dt_s;
    restAvg_s_ += in.dt_s;
  }
  if (rest_s_ < kPointRestS || !(restAvg_s_ > 0.0)) return;
  restTaken_ = true;
  const double ohms = r.ohmsAt(in.tempC);
  const double a = restA_s_ / restAvg_s_;
  if (std::fabs(a) > kPointMeanC * c) return;  // not a rest on average
  const double ocv = restV_s_ / restAvg_s_ - (std::isfinite(ohms) ? a * ohms : 0.0);
  pendingSocPct_ = socFromRestVolts(ocv, p, in.nominalVoltage);
}

double OcvReanchor::takeRestedPoint() noexcept {
  const double pct = pendingSocPct_;
  pendingSocPct_ = kNoValue;
  return pct;
}

}  // namespace xr
