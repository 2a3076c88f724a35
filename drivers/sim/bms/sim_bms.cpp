// SimBms (see sim_bms.h).
#include "drivers/sim/bms/sim_bms.h"

#include <algorithm>
#include <array>
#include <utility>

#include "can/bms_codec.h"
#include "core/bms_limits.h"

namespace xr::sim {
namespace {

// Linear interpolation in a (x ascending, y) table, flat beyond its ends.
template <std::size_t N>
double interp(const std::array<std::pair<double, double>, N>& t, double x) {
  if (x <= t.front().first) return t.front().second;
  for (std::size_t i = 1; i < N; ++i)
    if (x <= t[i].first)
      return t[i - 1].second +
             (t[i].second - t[i - 1].second) * (x - t[i - 1].first) / (t[i].first - t[i - 1].first);
  return t.back().second;
}

constexpr std::array<std::pair<double, double>, 5> kSocTaper{
    {{85, 1.0}, {90, 0.5}, {95, 0.2}, {98, 0.1}, {100, 0.1}}};
constexpr std::array<std::pair<double, double>, 2> kTempTaper{{{0, 0.0}, {10, 1.0}}};
constexpr double kIgnoreMarginA = 5.0;  // over CCL by more than this counts as ignored
constexpr double kWarnChargeA = 2.0;    // charging above this while warning counts as ignored
constexpr double kHighVoltageMarginV = 0.1;

}  // namespace

double SimBms::ccl(const SimBmsTruth& t) const {
  if (forcedCclA >= 0.0) return forcedCclA;
  return cclMaxA * interp(kSocTaper, t.socPct) * interp(kTempTaper, t.tempC);
}

bool SimBms::warning(const SimBmsTruth& t) const {
  return forcedWarning || t.batteryV > cvl() + kHighVoltageMarginV || (rec && cellMaxV(t) > kCellWarnV);
}

std::vector<CanFrame> SimBms::step(TimeNs now, const SimBmsTruth& t) {
  const bool ignored = t.batteryA > ccl(t) + kIgnoreMarginA || (warning(t) && t.batteryA > kWarnChargeA);
  if (!ignored) {
    ignoredSince_ = -1;
  } else if (ignoredSince_ < 0) {
    ignoredSince_ = now;
  } else if (now - ignoredSince_ > fromSec(openAfterS)) {
    open_ = true;
  }
  std::vector<CanFrame> out;
  if (!talking || now < nextSend_) return out;
  nextSend_ = now + fromSec(kPeriodS);
  out.push_back(can::encode351(cvl(), ccl(t), 200.0, 10.0));
  if (shortFrames) out.back().dlc = 4;
  out.push_back(rec ? can::encode355Rec(t.socPct, 100.0) : can::encode355(t.socPct, 100.0));
  out.push_back(can::encode356(t.batteryV, t.batteryA, t.tempC));
  out.push_back(can::encode35A(0, warning(t) ? bmswarn::HighVoltage : 0u));
  if (rec) out.push_back(can::encode373(cellMinV(t), cellMaxV(t), t.tempC, t.tempC));
  if (pylontech) out.push_back(can::encode359(0, warning(t) ? bmswarn::HighVoltage : 0u));
  return out;
}

}  // namespace xr::sim
