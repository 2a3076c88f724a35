#include "config/overrides.h"

#include "config/param_values.h"
#include "config/toml_values.h"

namespace xr {

std::vector<ConfigError> applyFlatOverrides(Params& p, const toml::table& table, std::string_view file) {
  std::vector<ConfigError> errs;
  Params next = p;
  for (auto&& [k, node] : table) {
    const std::string name(k.str());
    const int line = static_cast<int>(k.source().begin.line);
    const int column = static_cast<int>(k.source().begin.column);
    const ParamSpec* spec = findParam(name);
    if (!spec) {
      std::string msg = "unknown parameter";
      if (auto near = closestParamName(name); !near.empty()) msg += " (did you mean " + near + "?)";
      errs.push_back({std::string(file), line, column, name, msg});
      continue;
    }
    auto v = detail::paramValueFromNode(*spec, node);
    if (auto* why = std::get_if<std::string>(&v)) {
      errs.push_back({std::string(file), line, column, name, *why});
      continue;
    }
    setParamValue(next, *spec, std::get<ParamValue>(v));
  }
  for (auto& e : checkConsistency(next, file)) errs.push_back(std::move(e));
  // A flat override set applies whole or not at all, like a PATCH: a half-
  // applied set could leave Float above Bulk.
  if (errs.empty()) p = next;
  return errs;
}

}  // namespace xr
