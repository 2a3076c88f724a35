// make bench: how much faster than real time the whole closed loop runs,
// headless at --speed max. The headline is the 8-hour LFP charge scenario
// (scenarios/lfp-charge.toml); counters report simulated seconds per wall
// second ("x_realtime") and the cost of one 2.5 ms control tick.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "drivers/sim/ina228_model.h"
#include "drivers/sim/sim_world.h"
#include "sim_rig/sim_runner.h"

namespace {
using namespace xr;
using namespace xr::sim;

void runScenario(benchmark::State& state, double durationS) {
  const Scenario sc = loadScenario(XR_SOURCE_DIR "/scenarios/lfp-charge.toml");
  double simS = 0, ticks = 0;
  for (auto _ : state) {
    SimRunOptions o;
    o.scenario = sc;
    o.durationS = durationS;
    o.telemetryRateHz = 1.0;  // what a CSV at 1 Hz would need
    o.keepRows = false;
    SimRunner r(o);
    const SimRunResult res = r.run();
    simS += res.simulatedS;
    ticks += double(res.ticks);
    benchmark::DoNotOptimize(res.finalTruth.soc_pct);
  }
  state.counters["x_realtime"] = benchmark::Counter(simS, benchmark::Counter::kIsRate);
  state.counters["tick_ns"] =
      benchmark::Counter(ticks, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The headline figure (docs/performance.md): 8 simulated hours, one run.
void BM_LfpCharge8h(benchmark::State& state) { runScenario(state, 8 * 3600.0); }
BENCHMARK(BM_LfpCharge8h)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// The first 10 minutes (bulk at full output), repeated for a stabler figure.
void BM_LfpCharge10min(benchmark::State& state) { runScenario(state, 600.0); }
BENCHMARK(BM_LfpCharge10min)->Unit(benchmark::kMillisecond)->UseRealTime();

// The simulator alone: plant + chip models advancing one control period.
void BM_WorldStepOnly(benchmark::State& state) {
  WorldConfig c;
  HardwareSettings hw;
  SimWorld w(c, hw);
  w.simPwm().setDutyPercent(40);
  w.fieldEnable().set(true);
  TimeNs t = 0;
  for (auto _ : state) {
    t += fromUs(2500);
    w.advanceTo(t);
  }
  state.counters["x_realtime"] =
      benchmark::Counter(double(state.iterations()) * 0.0025, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WorldStepOnly);

// The same, with the ADS1115 in continuous 860 SPS conversion-ready mode and
// the world advanced to every ALERT/RDY edge before each 2.5 ms grid point
// (ready-edge pacing: ~2 extra advances per tick that must not step the plant).
void BM_WorldStepWithEdges(benchmark::State& state) {
  WorldConfig c;
  HardwareSettings hw;
  SimWorld w(c, hw);
  w.simPwm().setDutyPercent(40);
  w.fieldEnable().set(true);
  auto writeAds = [&](std::uint8_t reg, std::uint16_t v) {
    std::uint8_t b[3] = {reg, std::uint8_t(v >> 8), std::uint8_t(v)};
    I2cMsg m{hw.ads1115_address, false, b, 3};
    return w.i2c().transfer({&m, 1});
  };
  // Hi_thresh MSB = 1, Lo_thresh MSB = 0: ALERT/RDY is the conversion-ready pin;
  // then continuous AIN1-GND, +-4.096 V, 860 SPS, comparator queue enabled.
  if (writeAds(3, 0x8000) != 0 || writeAds(2, 0x0000) != 0 ||
      writeAds(1, std::uint16_t((5 << 12) | (1 << 9) | (7 << 5))) != 0) {
    state.SkipWithError("ADS1115 configuration refused");
    return;
  }
  TimeNs t = 0;
  std::uint64_t edges = 0;
  for (auto _ : state) {
    t += fromUs(2500);
    for (TimeNs e = w.ads().nextReadyEdge(); e >= 0 && e < t; e = w.ads().nextReadyEdge()) {
      w.advanceTo(e);
      ++edges;
    }
    w.advanceTo(t);
  }
  state.counters["edges_per_step"] = double(edges) / double(std::max<std::int64_t>(1, state.iterations()));
  state.counters["x_realtime"] =
      benchmark::Counter(double(state.iterations()) * 0.0025, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WorldStepWithEdges);

}  // namespace

BENCHMARK_MAIN();
