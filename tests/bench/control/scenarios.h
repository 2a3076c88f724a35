#pragma once
// The three Regulator::step workloads of the control-law benchmark, shared by
// the Google Benchmark binary and the callgrind driver.
#include "../../unit/control/reg_rig.h"

namespace xr::bench {

enum class Scenario { Bulk, Absorption, ShutdownRamp };

inline Params scenarioParams(Scenario s) {
  Params p;
  if (s == Scenario::Absorption) {
    p.bulkVoltageHoldMs = 1000;
    p.AbsorptionTimeoutMs = 86400000;  // stay in absorption
    p.absorptionCompleteTime = 3600000;
  }
  return p;
}

// Brings the rig to the steady state of the scenario.
inline void prepare(test::RegRig& r, Scenario s) {
  if (s != Scenario::Absorption) r.plant.voltsPerAmpSec = 0.0;  // the bank never fills: bulk forever
  if (s == Scenario::Absorption) {
    r.plant.Vocv = 14.35;
    r.plant.VocvMax = 14.39;
    r.plant.house = 30.0;  // a real load so CV keeps working
  }
  r.run(s == Scenario::Absorption ? 20.0 : 10.0);
}

// One measured tick. For the shutdown ramp, the operator toggles off/auto so
// most ticks are spent inside the ramp phases.
inline void tickScenario(test::RegRig& r, Scenario s, long i) {
  if (s == Scenario::ShutdownRamp) {
    const long k = i % 2800;  // 7 s cycle: ramp down 6 s, back up 1 s
    if (k == 0) r.reg.command({CommandType::Off, 0.0, false});
    if (k == 2400) r.reg.command({CommandType::Auto, 0.0, false});
  }
  r.tick();
}

}  // namespace xr::bench
