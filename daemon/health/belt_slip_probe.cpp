// BeltSlipDetector's sign C: the probe with the tach alone (docs/operations.md
// "Belt slip"). A slipping belt turns the alternator slower the more current
// it gives; the engine's speed does not depend on it. So when the tach falls
// fast under load, the current is held low for a few seconds: the speed
// rising then, and falling again when the current comes back, is the belt.
#include <algorithm>
#include <cmath>

#include "health/belt_slip.h"

namespace xr {

using namespace belt_k;

// Called once a second, after the ring holds this second. True on the
// second that completes a probe whose speed followed the current both ways.
bool BeltSlipDetector::probeSign(double& risePct, double& ampsBefore) noexcept {
  sinceProbeS_ += 1.0;
  const Second& now = ago(0);
  if (!now.field || engineHeard_ || latched_) {
    // Out of AUTO, or the engine's own speed is heard (sign A reads it):
    // no probe, and one under way is dropped (its cap released).
    probe_ = Probe::Idle;
    return false;
  }
  switch (probe_) {
    case Probe::Idle: {
      if (filled_ <= kFallWindowS || sinceProbeS_ < kProbeRearmS || !(ratedA_ > 0.0)) return false;
      double hi = 0.0;
      for (int i = 1; i <= kFallWindowS; ++i) hi = std::max(hi, ago(i).rpm);
      const double load = std::max(kProbeMinA, kProbeLoadShare * ratedA_);
      const bool fell = hi >= kMinRpm && now.rpm < hi * (1.0 - kFallShare);
      if (!fell || !(now.amps >= load)) return false;
      probe_ = Probe::Holding;
      probeS_ = 0;
      sinceProbeS_ = 0.0;
      beforeRpm_ = now.rpm;
      beforeAmps_ = now.amps;
      probeCap_ = kProbeCapShare * now.amps;
      return false;
    }
    case Probe::Holding:
      if (++probeS_ < kProbeS) return false;
      heldRpm_ = now.rpm;
      heldAmps_ = now.amps;
      probe_ = Probe::Releasing;
      probeS_ = 0;
      return false;
    case Probe::Releasing: {
      if (++probeS_ < kReleaseS) return false;
      probe_ = Probe::Idle;
      // The current fell, and the speed rose with it ...
      const bool currentFell = beforeAmps_ - heldAmps_ >= kProbeCurrentShare * beforeAmps_;
      const bool rose = heldRpm_ >= beforeRpm_ * (1.0 + kProbeRiseShare);
      // ... then the current came back, and the speed fell back (at least half way).
      const bool currentBack = now.amps - heldAmps_ >= 0.5 * (beforeAmps_ - heldAmps_);
      const bool fellBack = heldRpm_ - now.rpm >= 0.5 * (heldRpm_ - beforeRpm_);
      if (!(currentFell && rose && currentBack && fellBack)) return false;
      risePct = 100.0 * (heldRpm_ - beforeRpm_) / heldRpm_;
      ampsBefore = beforeAmps_;
      return true;
    }
  }
  return false;
}

}  // namespace xr
