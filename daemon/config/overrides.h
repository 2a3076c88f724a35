#pragma once
// Flat parameter overrides from a TOML table: a scenario's [config] table
// (DESIGN.md "Scenario file") or a [[events]] `set = { ... }` inline table.
// Keys are bare catalogue names (no group prefix). Pulls in toml++, so it
// lives apart from config.h.
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "config/config.h"
#include "params/params.h"

namespace xr {

// Applies every valid key of table to p; returns one error per bad key
// (unknown name + suggestion, wrong type, out of range), and leaves p
// untouched for those keys. Cross-parameter consistency is checked too.
std::vector<ConfigError> applyFlatOverrides(Params& p, const toml::table& table,
                                            std::string_view file = "scenario");

}  // namespace xr
