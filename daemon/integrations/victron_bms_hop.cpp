// VictronBmsHop (see victron_bms_hop.h).
#include "integrations/victron_bms_hop.h"

#include <cmath>

namespace xr::integrations {

namespace {
bool same(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

bool same(const BmsLimits& a, const BmsLimits& b) {
  return same(a.cvlV, b.cvlV) && same(a.cclA, b.cclA) && same(a.socPct, b.socPct) && same(a.tempC, b.tempC) &&
         a.chargeAllowed == b.chargeAllowed && a.source == b.source && a.stamp == b.stamp;
}
}  // namespace

BmsLimits toBmsLimits(const VictronLimits& v, TimeNs stamp) {
  BmsLimits b;
  b.cvlV = v.cvl_v;
  b.cclA = v.ccl_a;
  b.socPct = v.soc_pct;
  b.tempC = v.temp_c;
  b.chargeAllowed = v.allowToCharge != 0;
  b.source = BmsSource::VictronGx;
  b.stamp = stamp;
  return b;
}

void VictronBmsHop::operator()(const VictronLimits& v) {
  if (v.limitUpdates != seenUpdates_) {
    seenUpdates_ = v.limitUpdates;
    // The bridge calls as a limit arrives (its age is 0 then), so the
    // arrival is the control clock's newest tick, at most one tick old: a
    // stamp a little early only makes the limits go stale a little sooner.
    const TimeNs now = h_.latest().telemetry.now;
    if (now > 0) stamp_ = now;
  }
  const BmsLimits b = toBmsLimits(v, stamp_);
  if (posts_ > 0 && same(b, last_)) return;
  h_.bms.store(b);
  last_ = b;
  ++posts_;
}

}  // namespace xr::integrations
