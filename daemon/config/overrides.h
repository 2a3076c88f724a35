#pragma once
// Flat parameter overrides from a TOML table: a scenario's [config] table
// (docs/simulator.md "Scenario file") or a [[events]] `set = { ... }` inline table.
// Keys are bare catalogue names (no group prefix). Pulls in toml++, so it
// lives apart from config.h.
#include <toml++/toml.h>

#include <string_view>
#include <vector>

#include "config/config.h"
#include "params/params.h"

namespace xr {

// Applies table to p as a whole: on any error (unknown name + suggestion,
// wrong type, out of range, cross-parameter inconsistency) p is left
// unchanged and every error is returned.
std::vector<ConfigError> applyFlatOverrides(Params& p, const toml::table& table,
                                            std::string_view file = "scenario");

}  // namespace xr
