#pragma once
// The Victron GX's battery limits into the control law (docs/integrations.md). The GX
// bridge hands its newest VictronLimits to this hop on the integrations
// thread; the hop turns them into the same BmsLimits a BMS on CAN posts
// (core/bms_limits.h) and stores them in Handoffs::bms, which the control
// cycle copies at the start of each tick. The RT thread never waits: the
// hand-off is a seqlock and this hop is its only writer (the loader refuses
// a CAN BMS and a Victron GX together).
//
// `stamp` is on the control clock, so BmsStaleS is measured on the clock
// the regulator runs on (virtual time in --sim): each new CVL/CCL from the
// GX is stamped with the newest snapshot's telemetry.now. A poll that brings
// nothing new leaves the stamp alone, so a silent GX ages into
// REASON_BMS_STALE exactly like a silent CAN BMS.
#include <cstdint>

#include "core/bms_limits.h"
#include "integrations/victron_gx.h"
#include "runtime/handoffs.h"

namespace xr::integrations {

// Pure: what the control law reads from the GX's limits. Unknown values stay
// NaN (the limiter then uses BmsFallbackCapA for the current); an unknown
// AllowToCharge does not stop charging (the BMS has not said no).
BmsLimits toBmsLimits(const VictronLimits& v, TimeNs stamp);

class VictronBmsHop {
 public:
  explicit VictronBmsHop(rt::Handoffs& h) : h_(h) {}
  // A VictronLimitsSink; integrations thread only.
  void operator()(const VictronLimits& v);
  std::uint64_t posts() const { return posts_; }

 private:
  rt::Handoffs& h_;
  std::uint64_t seenUpdates_ = 0;
  TimeNs stamp_ = 0;  // control clock of the newest CVL/CCL (0 = none yet)
  BmsLimits last_{};
  std::uint64_t posts_ = 0;
};

}  // namespace xr::integrations
