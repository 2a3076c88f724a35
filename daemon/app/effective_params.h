#pragma once
// The parameters the daemon runs with, in layers (docs/configuration.md "One chain of values"): catalogue
// defaults < battery profile < file (with a scenario's [config]) < stored
// dashboard overrides. The profile is re-applied whenever a layer above it
// changes, so a dashboard change of BatteryProfile or BatteryCells moves
// every value the profile owns and nobody pinned.
#include <string>
#include <vector>

#include "app/stored_overrides.h"
#include "config/param_sources.h"

namespace xr::app {

// resolved: the stored overrides as resolveStoredOverrides() left them.
// Sets origins.dashboard to the overrides in force and re-applies the
// profile. When the result is inconsistent (a stored profile change that the
// file no longer allows), every dashboard override is set aside and *why says
// so: the file's values apply, never an unchecked set.
Params withDashboardLayer(const Params& fileParams, const OverrideResolution& resolved, ParamOrigins& origins,
                          std::string* why);

// A PATCH: `patched` are the names it sets (joining the dashboard layer),
// `p` the current set with them written in. Re-applies the profile.
Params withPatch(const Params& p, const std::vector<std::string>& patched, ParamOrigins& origins);

}  // namespace xr::app
