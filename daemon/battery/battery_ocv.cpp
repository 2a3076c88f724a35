// The first SoC of a lead-acid bank from its rested voltage (docs/batteries.md
// "State of charge at first start"). A fresh ledger does not know the SoC;
// a lead-acid bank's open-circuit voltage tells it within some points, so
// once the bank has rested the monitor starts counting from that estimate
// and says it is one. LiFePO4's voltage is flat from 20 % to 90 % (docs/sources.md
// §3.1: 12.85-13.24 V), so a LiFePO4 or custom bank stays unknown until its
// first full charge or a value set by hand.
#include <algorithm>
#include <cmath>

#include "battery/battery_monitor.h"

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

// "At rest" for the estimate: at most 2 % of the capacity flowing (a few
// amps of house load on a 200 Ah bank move the voltage by hundredths), the
// alternator not charging, for 30 s. A true OCV wants hours of rest
// (docs/sources.md P3.5); the figure is shown as an estimate for that reason.
constexpr double kRestCurrentC = 0.02;
constexpr double kRestSeconds = 30.0;

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

bool BatteryMonitor::leadAcidAtRest(double amps, double volts, double altAmps) const noexcept {
  const bool alternatorOff = !std::isfinite(altAmps) || altAmps <= p_.CurrentThreshold;
  return isLeadAcid(p_) && std::isfinite(amps) && std::isfinite(volts) &&
         std::fabs(amps) <= kRestCurrentC * p_.BatteryCapacity_Ah && alternatorOff;
}

double BatteryMonitor::socFromRestVolts(double volts) const noexcept {
  // Per 12 V of bank: BatteryCells when set, else the bank class's 6 per 12 V.
  const double cells = p_.BatteryCells > 0 ? p_.BatteryCells : 6.0 * nominalVoltage_ / 12.0;
  return socFromRestVoltage12(volts * 6.0 / cells);
}

void BatteryMonitor::estimateSocAtRest(double dt_s, double amps, double volts, double altAmps) noexcept {
  if (socSource() != SocSource::Unknown || !isLeadAcid(p_) || !(dt_s > 0.0)) {
    restTimer_s_ = restVoltSum_ = 0.0;
    return;
  }
  if (!leadAcidAtRest(amps, volts, altAmps)) {
    restTimer_s_ = restVoltSum_ = 0.0;
    return;
  }
  restTimer_s_ += dt_s;
  restVoltSum_ += volts * dt_s;
  if (restTimer_s_ < kRestSeconds) return;
  ledger_.CoulombCount_Ah = p_.BatteryCapacity_Ah * socFromRestVolts(restVoltSum_ / restTimer_s_) / 100.0;
  ledger_.coulombAccumulator_Ah = 0.0;
  setSocSource(SocSource::OcvEstimate);
  restTimer_s_ = restVoltSum_ = 0.0;
}

}  // namespace xr
