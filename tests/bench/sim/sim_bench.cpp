// make bench: how much faster than real time the whole closed loop runs,
// headless at --speed max. The headline is the 8-hour LFP charge scenario
// (scenarios/lfp-charge.toml); counters report simulated seconds per wall
// second ("x_realtime") and the cost of one 2.5 ms control tick.
#include <benchmark/benchmark.h>

#include "drivers/sim/ina228_model.h"
#include "drivers/sim/runner/sim_runner.h"
#include "drivers/sim/sim_world.h"

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
  state.counters["tick_ns"] = benchmark::Counter(ticks, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The headline: 8 simulated hours, one run.
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

}  // namespace

BENCHMARK_MAIN();
