// FastSampleRates on its own: the dv/dt EMA only on sample pairs 1-100 ms
// apart, and the load-dump tiers at their thresholds, just below, and only
// in INA228 fast mode.
#include "protection/fast_samples.h"

#include <gtest/gtest.h>

#include "part_log.h"

namespace xr::test {
namespace {

struct RateRig {
  Params p;
  FastSampleRates rates;
  Inputs in;
  TimeNs t = fromSec(100.0);
  double bcur = 10.0;
  void sample(double ibv, double dBcurDt, TimeNs dt = fromMs(5), bool fast = true) {
    t += dt;
    bcur += dBcurDt * toSec(dt);
    in.now = t;
    in.IBV = Reading{ibv, t, true};
    in.Bcur = Reading{bcur, t, true};
    in.inaFastModeActive = fast;
    rates.update(in, p);
  }
};

TEST(FastSampleRatesPart, DvdtFollowsPairsInsideTheWindowAndHoldsOutsideIt) {
  RateRig r;
  r.sample(13.50, 0.0);
  r.sample(13.55, 0.0);  // 10 V/s over 5 ms
  EXPECT_NEAR(r.rates.dvdt(), r.p.DvdtAlpha * 10.0, 1e-9);
  const double held = r.rates.dvdt();
  r.sample(14.0, 0.0, fromMs(200));  // slow-mode pair: rejected
  EXPECT_DOUBLE_EQ(r.rates.dvdt(), held);
}

TEST(FastSampleRatesPart, Tier1FiresOnOneSampleOverItsThresholdNotAtIt) {
  RateRig r;
  r.sample(13.5, 0.0);
  r.sample(13.5, r.p.LoadDumpDtThresh1 * 0.99);
  EXPECT_FALSE(r.rates.loadDump());  // over tier 2's threshold, but only once
  r.sample(13.5, 0.0);
  r.sample(13.5, r.p.LoadDumpDtThresh1 * 1.01);
  EXPECT_TRUE(r.rates.loadDump());
  r.sample(13.5, 0.0);
  EXPECT_FALSE(r.rates.loadDump());  // one tick: the next sample decides again
}

TEST(FastSampleRatesPart, Tier3NeedsThreeConsecutiveSamplesAndFastMode) {
  RateRig r;
  const double rate = (r.p.LoadDumpDtThresh3 + r.p.LoadDumpDtThresh) / 2.0;  // tier 3 only
  r.sample(13.5, 0.0);
  r.sample(13.5, rate);
  r.sample(13.5, rate);
  EXPECT_FALSE(r.rates.loadDump());
  r.sample(13.5, rate);
  EXPECT_TRUE(r.rates.loadDump());
  RateRig slow;
  slow.sample(13.5, 0.0, fromMs(5), false);
  slow.sample(13.5, slow.p.LoadDumpDtThresh1 * 2.0, fromMs(5), false);
  EXPECT_FALSE(slow.rates.loadDump());  // slow mode: not acted on
  EXPECT_GT(slow.rates.dBcurDt(), slow.p.LoadDumpDtThresh1);
}

}  // namespace
}  // namespace xr::test
