// Small driver for `valgrind --tool=callgrind`: prepares a scenario, then runs
// N ticks inside regulator_ticks() so the instructions per tick can be read
// from that function's inclusive cost (callgrind_annotate --inclusive=yes).
// Usage: bench_regulator_callgrind bulk|absorption|shutdown N
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "scenarios.h"

__attribute__((noinline)) void regulator_ticks(xr::test::RegRig& r, xr::bench::Scenario sc, long n) {
  for (long i = 0; i < n; ++i) xr::bench::tickScenario(r, sc, i);
}

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s bulk|absorption|shutdown N\n", argv[0]);
    return 2;
  }
  const xr::bench::Scenario sc = !std::strcmp(argv[1], "absorption") ? xr::bench::Scenario::Absorption
                                 : !std::strcmp(argv[1], "shutdown") ? xr::bench::Scenario::ShutdownRamp
                                                                     : xr::bench::Scenario::Bulk;
  const long n = std::atol(argv[2]);
  xr::test::RegRig r(xr::bench::scenarioParams(sc));
  xr::bench::prepare(r, sc);
  regulator_ticks(r, sc, n);
  std::printf("duty %.3f field %d cv %d\n", r.out->dutyPct, r.out->fieldEnable ? 1 : 0,
              r.out->telemetry.control.voltageControlActive ? 1 : 0);
  return 0;
}
