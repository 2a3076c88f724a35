// CapacityTracker (docs/batteries.md "Measured capacity").
#include "battery/capacity_tracker.h"

#include <cmath>

namespace xr {

using namespace capacity_k;

void CapacityTracker::addAh(double correctedAh, double elapsed_s) noexcept {
  if (l_.AnchorValid != 1.0) return;
  if (std::isfinite(correctedAh)) l_.NetAh += correctedAh;
  if (std::isfinite(elapsed_s) && elapsed_s > 0.0) l_.AnchorAge_s += elapsed_s;
}

void CapacityTracker::anchor(double socPct) noexcept {
  l_.AnchorValid = 1.0;
  l_.AnchorSocPct = socPct;
  l_.NetAh = 0.0;
  l_.AnchorAge_s = 0.0;
}

CapacityPointResult CapacityTracker::knownSoc(double socPct, bool full, double configuredAh) noexcept {
  if (!std::isfinite(socPct) || socPct < 0.0 || socPct > 100.0) return CapacityPointResult::Held;
  if (l_.AnchorValid != 1.0 || l_.AnchorAge_s > kMaxAnchorAge_s) {
    anchor(socPct);
    return CapacityPointResult::Anchored;
  }
  const double swingPct = socPct - l_.AnchorSocPct;
  if (std::fabs(swingPct) < kMinSwingPct) {
    // Too small to measure: keep the older point (the swing may still grow),
    // unless this is a full charge, which is the better point.
    if (!full) return CapacityPointResult::Held;
    anchor(socPct);
    return CapacityPointResult::Anchored;
  }
  const double ah = l_.NetAh;
  const double swing = std::fabs(swingPct) / 100.0;
  const double sample = std::fabs(ah) / swing;
  // The count must have moved the way the SoC did, by a plausible amount.
  const bool sameWay = (ah > 0.0) == (swingPct > 0.0);
  const bool plausible = sample >= kMinShare * configuredAh && sample <= kMaxShare * configuredAh;
  anchor(socPct);
  if (!sameWay || !plausible) return CapacityPointResult::Rejected;
  l_.SumAh = l_.SumAh * kFade + std::fabs(ah);
  l_.SumSwing = l_.SumSwing * kFade + swing;
  l_.Cycles += 1.0;
  lastSampleAh_ = sample;
  lastSwingPct_ = std::fabs(swingPct);
  return CapacityPointResult::Measured;
}

double CapacityTracker::measuredAh() const noexcept {
  if (l_.Cycles < kMinCycles || !(l_.SumSwing > 0.0)) return std::nan("");
  return l_.SumAh / l_.SumSwing;
}

void CapacityTracker::restore(const CapacityLedger& in) noexcept {
  const bool sane = std::isfinite(in.SumAh) && in.SumAh >= 0.0 && std::isfinite(in.SumSwing) &&
                    in.SumSwing >= 0.0 && std::isfinite(in.Cycles) && in.Cycles >= 0.0 && in.Cycles < 1e9 &&
                    std::isfinite(in.AnchorSocPct) && in.AnchorSocPct >= 0.0 && in.AnchorSocPct <= 100.0 &&
                    std::isfinite(in.NetAh) && std::isfinite(in.AnchorAge_s) && in.AnchorAge_s >= 0.0 &&
                    (in.AnchorValid == 0.0 || in.AnchorValid == 1.0);
  l_ = sane ? in : CapacityLedger{};
}

}  // namespace xr
