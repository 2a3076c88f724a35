#pragma once
// Where each effective parameter value comes from (docs/configuration.md): the catalogue
// default, the battery profile, the configuration file (with a scenario's
// [config]) or the dashboard (PATCH /api/params, stored overrides). Later
// layers win: default < profile < file < dashboard.
#include <string>
#include <string_view>

#include "config/battery_profiles.h"
#include "config/settings.h"

namespace xr {

// SetupPending: lowered to the "not set up" limits (config/setup_pending.h),
// whatever set it.
enum class ParamSource { Default, Profile, File, Dashboard, SetupPending };
// "default", "profile", "file", "dashboard", "not set up"
std::string_view toString(ParamSource s);

struct ParamOrigins {
  NameSet file;          // written in the file or a scenario's [config]
  NameSet profile;       // filled by the battery profile
  NameSet dashboard;     // stored dashboard overrides in force
  NameSet setupPending;  // lowered because no battery type is chosen yet
  // A simulator scenario describes a boat that is set up: its [config] is
  // the installer's, and the "not set up" limits would change every run.
  bool assumeSetUp = false;
  // A battery type is named (file, [config] or dashboard), or assumeSetUp.
  bool setUp() const;
  ParamSource of(std::string_view name) const;
};

// The effective parameters from the values in p (file and dashboard values
// already written into it): the profile re-applied with everything the file
// and the dashboard set pinned. origins.profile is updated.
Params applyLayers(const Params& p, ParamOrigins& origins);

// What the regulator runs with: the configured set (applyLayers' result,
// kept unlowered so that choosing a battery later starts from what the file
// and the dashboard really say), lowered to the "not set up" limits until a
// battery type is chosen. origins.setupPending is updated.
Params runningParams(const Params& configured, ParamOrigins& origins);

// `--print-config`: the effective configuration as TOML, every value with a
// comment naming its source (# default, # profile, # file, # dashboard);
// settings are # file when they differ from the built-in default.
std::string effectiveConfigText(const Settings& settings, const Params& p, const ParamOrigins& origins);

}  // namespace xr
