// Regulator::step benchmark (docs/architecture.md): bulk, absorption (CV active,
// protections armed) and a shutdown ramp. Each iteration is one 2.5 ms tick:
// build Inputs from the test plant, Regulator::step, advance the plant (the
// plant and input construction are a few ns of the figure).
#include <benchmark/benchmark.h>

#include "scenarios.h"

namespace {

void run(benchmark::State& state, xr::bench::Scenario sc) {
  xr::test::RegRig r(xr::bench::scenarioParams(sc));
  xr::bench::prepare(r, sc);
  long i = 0;
  for (auto _ : state) {
    xr::bench::tickScenario(r, sc, i++);
    benchmark::DoNotOptimize(r.out->dutyPct);
  }
  state.counters["field_on"] = r.out->fieldEnable ? 1 : 0;
  state.counters["cv_active"] = r.out->telemetry.control.voltageControlActive ? 1 : 0;
}

void BM_RegulatorStep_Bulk(benchmark::State& s) { run(s, xr::bench::Scenario::Bulk); }
void BM_RegulatorStep_Absorption(benchmark::State& s) { run(s, xr::bench::Scenario::Absorption); }
void BM_RegulatorStep_ShutdownRamp(benchmark::State& s) { run(s, xr::bench::Scenario::ShutdownRamp); }

BENCHMARK(BM_RegulatorStep_Bulk)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_RegulatorStep_Absorption)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_RegulatorStep_ShutdownRamp)->Repetitions(5)->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
