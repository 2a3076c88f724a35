#include "app/param_change_text.h"

#include <algorithm>
#include <cstdio>

namespace xr::app {

namespace {

// Enough digits for any catalogue value (resolutions of 0.001) without the
// 17-digit noise of a binary double.
std::string valueText(const ParamSpec& spec, double v) {
  if (spec.kind == ParamKind::Bool) return v != 0.0 ? "on" : "off";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

std::string paramChangeText(const Params& before, const Params& after, const std::vector<std::string>& named,
                            const std::string& source) {
  std::string list;
  for (const ParamSpec& spec : catalogue()) {
    const bool asked = std::find(named.begin(), named.end(), spec.name) != named.end();
    const std::size_t n = spec.kind == ParamKind::Table ? RPM_TABLE_SIZE : 1;
    for (std::size_t i = 0; i < n; ++i) {
      const double a = spec.get(before, i), b = spec.get(after, i);
      if (a == b) continue;
      if (!list.empty()) list += "; ";
      list += spec.name;
      if (spec.kind == ParamKind::Table) list += " point " + std::to_string(i + 1);
      list += " " + valueText(spec, a) + " \u2192 " + valueText(spec, b);
      if (!asked) list += " (follows the battery profile)";
    }
  }
  if (list.empty()) return {};
  return "Settings changed by " + (source.empty() ? std::string("the web API") : source) + ": " + list;
}

}  // namespace xr::app
