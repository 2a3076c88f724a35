#pragma once
// Where each effective parameter value comes from (issue 21): the catalogue
// default, the battery profile, the configuration file (with a scenario's
// [config]) or the dashboard (PATCH /api/params, stored overrides). Later
// layers win: default < profile < file < dashboard.
#include <string>
#include <string_view>

#include "config/battery_profiles.h"
#include "config/settings.h"

namespace xr {

enum class ParamSource { Default, Profile, File, Dashboard };
std::string_view toString(ParamSource s);  // "default", "profile", "file", "dashboard"

struct ParamOrigins {
  NameSet file;       // written in the file or a scenario's [config]
  NameSet profile;    // filled by the battery profile
  NameSet dashboard;  // stored dashboard overrides in force
  ParamSource of(std::string_view name) const;
};

// The effective parameters from the values in p (file and dashboard values
// already written into it): the profile re-applied with everything the file
// and the dashboard set pinned. origins.profile is updated.
Params applyLayers(const Params& p, ParamOrigins& origins);

// `--print-config`: the effective configuration as TOML, every value with a
// comment naming its source (# default, # profile, # file, # dashboard);
// settings are # file when they differ from the built-in default.
std::string effectiveConfigText(const Settings& settings, const Params& p, const ParamOrigins& origins);

}  // namespace xr
