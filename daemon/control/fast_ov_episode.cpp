// FastOvEpisode: one fast over-voltage episode as the control law sees it.
#include "control/fast_ov_episode.h"

#include <algorithm>

#include "core/finite.h"
#include "params/constants.h"

namespace xr {

EpisodeOutcome FastOvEpisode::update(const EpisodeInputs& in) noexcept {
  const FastOvVerdict& ov = in.ov;
  EpisodeOutcome out;
  clampActive_ = ov.fastOvClampActive;
  capA_ = ov.fastOvCurrentCap;
  if (ov.zeroSetpointLimited && !loadDumpInEpisode_)
    dumpAcceptA_ = in.bcurSlowPrimed ? in.bcurSlowA : kNoValue;
  if (ov.zeroSetpointLimited) loadDumpInEpisode_ = true;
  if (wasActive_ && !clampActive_) {
    out.cleared = true;
    // After the original firmware: a load dump snapped cv_I to 0 and bled
    // its AW cap; reseed (cap cleared) so the recovery starts from the
    // current the bank needs now. Group 1/2/3 clamps keep the original slow
    // AW recovery: their current was too high, a reseed would restore it.
    if (loadDumpInEpisode_) {
      // The bank at its target accepted dumpAcceptA_ before the load went;
      // what is still drawn beside it is the alternator current less the
      // battery's, now. Their sum holds the target. The inner loop's
      // filtered current still carries the dumped load (~1 s behind):
      // seeding from it drove the bank back over the target and kept the
      // field off while an AGM's charge overpotential relaxed (an engine
      // dropped to idle while cruising). Without a battery current the
      // original firmware's bumpless reseed stands.
      out.reseed = true;
      if (finite(dumpAcceptA_) && finite(in.Bcur) && finite(in.measuredAmps))
        out.reseedAtA = std::max(0.0, dumpAcceptA_ + (in.measuredAmps - in.Bcur));
      dumpAcceptA_ = kNoValue;
    }
    loadDumpInEpisode_ = false;
  }
  wasActive_ = clampActive_;
  return out;
}

bool FastOvEpisode::updateOvershootLatch(bool voltageControlActive, double IBV, double target) noexcept {
  if (cvOvershootBypass_ &&
      (!voltageControlActive || !finite(IBV) || IBV < target + k::CV_OVERSHOOT_RELEASE_V))
    cvOvershootBypass_ = false;
  if (voltageControlActive && clampActive_) cvOvershootBypass_ = true;
  return cvOvershootBypass_;
}

}  // namespace xr
