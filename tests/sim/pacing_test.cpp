// ADS1115 pacing through the whole loop (docs/architecture.md targets, on virtual time):
// with ALERT/RDY wired (the default line), every conversion is used — CH1
// >= 400 Hz and every channel >= 10 Hz — and charging works as before; with
// the line not wired (-1), single-shot pacing gives one conversion per tick.
#include "closed_loop.h"

namespace xr::sim::test {
namespace {

SimRunResult runPacing(int readyLine) {
  SimRunOptions o;
  o.scenario = parseScenario(R"(
name = "pacing"
duration_s = 120
seed = 3
[battery]
chemistry = "lifepo4"
capacity_ah = 400
soc_pct = 40
[engine]
rpm = 1800
)",
                             "inline.toml");
  o.settings.hardware.ads_alert_rdy_line = readyLine;
  o.telemetryRateHz = 1.0;
  SimRunner r(o);
  SimRunResult res = r.run();
  EXPECT_EQ(res.adsProtocolErrors, 0u);
  EXPECT_FALSE(res.finalFieldEnable);
  return res;
}

TEST(ClosedLoopPacing, ReadyEdgesGiveCh1Above400HzAndEveryChannelAbove10Hz) {
  const SimRunResult res = runPacing(27);
  EXPECT_GT(res.loop.adsEdges, 100000u);  // ~860 per simulated second
  EXPECT_GE(res.loop.ch1SampleRateHz, 400.0);
  for (double hz : res.loop.adsChannelRateHz) EXPECT_GE(hz, 10.0);
  EXPECT_FALSE(res.health.adsEdgeFallback);
  // The alternator is charging under control with these samples.
  const SimRow* last = at(res, 110.0);
  ASSERT_NE(last, nullptr);
  EXPECT_GT(last->plant.alt_a, 20.0);
  EXPECT_GT(last->telemetry.duty_pct, 0.0);
}

TEST(ClosedLoopPacing, NotWiredFallsToOneConversionPerTick) {
  const SimRunResult res = runPacing(-1);
  EXPECT_EQ(res.loop.adsEdges, 0u);
  EXPECT_LT(res.loop.ch1SampleRateHz, 201.0);
  EXPECT_GE(res.loop.ch1SampleRateHz, 190.0);
  for (double hz : res.loop.adsChannelRateHz) EXPECT_GE(hz, 10.0);
  const SimRow* last = at(res, 110.0);
  ASSERT_NE(last, nullptr);
  EXPECT_GT(last->plant.alt_a, 20.0);
}

}  // namespace
}  // namespace xr::sim::test
