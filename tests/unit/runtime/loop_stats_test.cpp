#include "runtime/loop_stats.h"

#include <gtest/gtest.h>

namespace xr::rt {
namespace {

TEST(LatencyHistogram, EmptyIsZero) {
  LatencyHistogram h;
  EXPECT_EQ(h.quantile(0.5), 0);
  EXPECT_EQ(h.max(), 0);
}

TEST(LatencyHistogram, QuantilesResolveToTheBinUpperEdgeCappedAtMax) {
  LatencyHistogram h;
  for (int i = 0; i < 98; ++i) h.add(fromUs(5));  // bin [0,10)
  h.add(fromUs(150));                             // bin [150,160)
  h.add(fromUs(1234));
  EXPECT_EQ(h.quantile(0.50), fromUs(10));
  EXPECT_EQ(h.quantile(0.98), fromUs(10));
  EXPECT_EQ(h.quantile(0.99), fromUs(160));
  EXPECT_EQ(h.quantile(1.0), fromUs(1234));
  EXPECT_EQ(h.max(), fromUs(1234));
  EXPECT_EQ(h.countBelow(fromUs(100)), 98u);
  EXPECT_EQ(h.countBelow(fromUs(200)), 99u);
}

TEST(LatencyHistogram, HugeValuesLandInOverflowAndKeepExactMax) {
  LatencyHistogram h;
  h.add(fromMs(50));
  EXPECT_EQ(h.quantile(0.5), fromMs(50));
  EXPECT_EQ(h.max(), fromMs(50));
  EXPECT_EQ(h.countBelow(fromMs(1)), 0u);
}

TEST(LatencyHistogram, NegativeErrorCountsByMagnitude) {
  LatencyHistogram h;
  h.add(-fromUs(30));
  EXPECT_EQ(h.max(), fromUs(30));
}

TEST(LoopStats, SummaryReportsComputeIoAndOverruns) {
  LoopStats s;
  for (int i = 0; i < 100; ++i) {
    s.onCompute(fromUs(20));
    s.onIo(fromUs(300));
    s.onTick();
  }
  s.onOverrun(2);
  const auto sum = s.summary();
  EXPECT_EQ(sum.ticks, 100u);
  EXPECT_EQ(sum.overruns, 2u);
  EXPECT_DOUBLE_EQ(sum.computeP50Us, 20.0);
  EXPECT_DOUBLE_EQ(sum.ioMaxUs, 300.0);
  EXPECT_FALSE(sum.periodMeasured);
}

TEST(LoopStats, ChannelRatesUseOneSecondWindows) {
  LoopStats s;
  TimeNs t = 0;
  for (int i = 0; i <= 1000; ++i, t += fromMs(1)) {
    // CH1 every ms, CH0 every 10 ms, CH2/CH3 never
    s.onSamples(t, {i % 10 == 0 ? 1u : 0u, 1u, 0u, 0u}, i % 2 == 0);
  }
  const auto sum = s.summary();
  EXPECT_NEAR(sum.ch1SampleRateHz, 1000.0, 2.0);
  EXPECT_NEAR(sum.adsChannelRateHz[0], 100.0, 2.0);
  EXPECT_EQ(sum.adsChannelRateHz[2], 0.0);
  EXPECT_NEAR(sum.inaSampleRateHz, 500.0, 2.0);
  EXPECT_NEAR(sum.windowS, 1.0, 0.01);
}

TEST(LoopStats, TotalsGiveTheSameRatesAsPerTickCounts) {
  // onSampleTotals (cumulative counts, differenced per window) must equal
  // onSamples (per-tick counts summed), bit for bit, also across a wrap of
  // the 32-bit totals and with uneven arrivals.
  LoopStats perTick, totals;
  std::array<std::uint32_t, 4> cum{0xFFFFFF00u, 7u, 0xFFFFFFFFu, 0u};
  const std::array<std::uint32_t, 4> start = cum;
  // The first tick brings everything counted before it (as ControlCycle
  // always did: its previous counts start at 0).
  perTick.onSamples(0, start, false);
  totals.onSampleTotals(0, cum, false);
  TimeNs t = 0;
  for (int i = 1; i <= 5000; ++i) {
    t += fromUs(2500) + (i % 3) * 1000;
    const std::array<std::uint32_t, 4> add{static_cast<std::uint32_t>(i % 3), 1u + (i % 2),
                                           i % 5 == 0 ? 1u : 0u, i % 7 == 0 ? 2u : 0u};
    for (std::size_t c = 0; c < 4; ++c) cum[c] += add[c];
    perTick.onSamples(t, add, i % 2 == 0);
    totals.onSampleTotals(t, cum, i % 2 == 0);
    if (i % 97 == 0) {
      const auto a = perTick.summary(), b = totals.summary();
      for (std::size_t c = 0; c < 4; ++c) EXPECT_EQ(a.adsChannelRateHz[c], b.adsChannelRateHz[c]) << i;
      EXPECT_EQ(a.inaSampleRateHz, b.inaSampleRateHz);
      EXPECT_EQ(a.windowS, b.windowS);
    }
  }
  EXPECT_LT(cum[0], start[0]) << "the totals wrapped";
  EXPECT_GT(totals.summary().ch1SampleRateHz, 500.0);
}

}  // namespace
}  // namespace xr::rt
