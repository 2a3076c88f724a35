// FastOvEpisode on its own: the clearing edge (and only it) opens the fast
// rise; after a load dump the voltage loop is reseeded at what the bank
// accepted before it plus the load still drawn; a Group 1/2/3 clamp alone
// asks no reseed; the CV overshoot latch releases at the release band.
#include "control/fast_ov_episode.h"

#include <gtest/gtest.h>

#include "params/constants.h"

namespace xr {
namespace {

EpisodeInputs clamp(bool active, bool dump) {
  EpisodeInputs in;
  in.ov.fastOvClampActive = active;
  in.ov.zeroSetpointLimited = dump;
  in.ov.fastOvCurrentCap = active ? 0.0 : 1e300;
  in.bcurSlowPrimed = true;
  in.bcurSlowA = 12.0;  // the bank accepted 12 A before the dump
  in.Bcur = -3.0;
  in.measuredAmps = 20.0;  // 23 A of load still drawn beside it
  return in;
}

TEST(FastOvEpisodePart, AfterALoadDumpTheReseedIsAcceptedPlusLoad) {
  FastOvEpisode e;
  EXPECT_FALSE(e.update(clamp(true, true)).cleared);
  EpisodeInputs later = clamp(true, false);
  later.bcurSlowA = 99.0;  // the first dump tick's value counts, not a later one
  EXPECT_FALSE(e.update(later).cleared);
  const EpisodeOutcome o = e.update(clamp(false, false));
  EXPECT_TRUE(o.cleared);
  EXPECT_TRUE(o.reseed);
  EXPECT_DOUBLE_EQ(o.reseedAtA, 12.0 + (20.0 - -3.0));
  EXPECT_FALSE(e.update(clamp(false, false)).cleared);  // the edge only
}

TEST(FastOvEpisodePart, AClampWithoutADumpAsksNoReseed) {
  FastOvEpisode e;
  e.update(clamp(true, false));
  const EpisodeOutcome o = e.update(clamp(false, false));
  EXPECT_TRUE(o.cleared);
  EXPECT_FALSE(o.reseed);
}

TEST(FastOvEpisodePart, OvershootLatchReleasesUnderTheBand) {
  FastOvEpisode e;
  e.update(clamp(true, false));
  EXPECT_TRUE(e.updateOvershootLatch(true, 14.6, 14.4));
  e.update(clamp(false, false));
  EXPECT_TRUE(e.updateOvershootLatch(true, 14.4 + k::CV_OVERSHOOT_RELEASE_V + 0.001, 14.4));
  EXPECT_FALSE(e.updateOvershootLatch(true, 14.4 + k::CV_OVERSHOOT_RELEASE_V - 0.001, 14.4));
  e.update(clamp(true, false));
  EXPECT_FALSE(e.updateOvershootLatch(false, 14.6, 14.4));  // not in CV: never latched
}

}  // namespace
}  // namespace xr
