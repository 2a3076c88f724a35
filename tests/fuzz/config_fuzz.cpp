// libFuzzer target ("a fuzzer for the config loader"): arbitrary
// bytes as xregulator.toml through loadConfigString, the loader the daemon and
// --check-config use. Findings: a crash, a sanitizer report, an exception out
// of the loader (it promises a list of errors, never a throw), or a file it
// accepts although the values the daemon would run with are out of range or
// inconsistent (the "checked as one set" rule, docs/configuration.md).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "config/config.h"
#include "params/params.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const xr::LoadResult r = xr::loadConfigString(text, "fuzz.toml");
  if (r.config.has_value() != r.errors.empty()) __builtin_trap();  // exactly one of the two
  for (const auto& e : r.errors)
    if (e.message.empty()) __builtin_trap();  // every error says what is wrong
  if (!r.ok()) return 0;
  const xr::Params& p = r.config->params;
  for (const xr::ParamSpec& spec : xr::catalogue()) {
    const std::size_t n = spec.kind == xr::ParamKind::Table ? xr::RPM_TABLE_SIZE : 1;
    for (std::size_t i = 0; i < n; ++i) {
      const double v = spec.get(p, i);
      if (!std::isfinite(v) || v < spec.min || v > spec.max) __builtin_trap();
    }
  }
  if (!xr::checkConsistency(p).empty()) __builtin_trap();
  return 0;
}
