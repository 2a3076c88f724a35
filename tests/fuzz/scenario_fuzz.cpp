// libFuzzer target ("a fuzzer for the scenario loader"): arbitrary
// bytes as a scenario file through parseScenario, then its [config] overrides
// onto the default parameters, as `xregulatord --sim --scenario` does. A bad
// file must end in ScenarioError ("file:line: ..."), which the daemon turns
// into exit 64. Findings: a crash, a sanitizer report, any other exception,
// or an accepted scenario whose events are not in time order or whose
// numbers are not finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "drivers/sim/scenario.h"
#include "params/params.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const xr::sim::Scenario s = xr::sim::parseScenario(text, "fuzz.toml");
    if (!std::isfinite(s.duration_s) || s.duration_s <= 0) __builtin_trap();
    double last = 0.0;
    for (const auto& e : s.events) {
      if (!std::isfinite(e.at_s) || e.at_s < last) __builtin_trap();
      last = e.at_s;
    }
    xr::Params p;
    xr::sim::applyOverrides(p, s.config, s.source);
  } catch (const xr::sim::ScenarioError&) {
    // the expected answer to a bad file
  }
  return 0;
}
