#include "config/param_sources.h"

#include <sstream>

#include "config/format.h"
#include "config/param_values.h"
#include "config/settings_schema.h"
#include "config/setup_pending.h"
#include "params/derived.h"

namespace xr {

std::string_view toString(ParamSource s) {
  switch (s) {
    case ParamSource::Default:
      return "default";
    case ParamSource::Profile:
      return "profile";
    case ParamSource::File:
      return "file";
    case ParamSource::Dashboard:
      return "dashboard";
    case ParamSource::SetupPending:
      return "not set up";
  }
  return "default";
}

bool ParamOrigins::setUp() const { return assumeSetUp || batteryChosen(file, dashboard); }

ParamSource ParamOrigins::of(std::string_view name) const {
  if (setupPending.count(name)) return ParamSource::SetupPending;
  if (dashboard.count(name)) return ParamSource::Dashboard;
  if (file.count(name)) return ParamSource::File;
  if (profile.count(name)) return ParamSource::Profile;
  return ParamSource::Default;
}

Params applyLayers(const Params& p, ParamOrigins& origins) {
  NameSet pinned = origins.file;
  pinned.insert(origins.dashboard.begin(), origins.dashboard.end());
  ProfileApplied r = applyBatteryProfile(p, pinned);
  origins.profile = std::move(r.setByProfile);
  return r.params;
}

namespace {

// Nobody named the bank's size: no bank voltage and no cell count in the
// file, a scenario's [config] or the dashboard. The class is then read from
// the battery (params/params.h SetupBankFromBattery).
bool bankSizeUnnamed(const Params& p, const ParamOrigins& origins) {
  for (const NameSet* names : {&origins.file, &origins.dashboard}) {
    for (const auto& name : *names) {
      if (name == "BatteryCells") {
        if (p.BatteryCells > 0) return false;  // 0 (the shipped file's) = from the voltage class
        continue;
      }
      const ParamSpec* spec = findParam(name);
      if (spec && spec->kind == ParamKind::Float && isBankVoltage(*spec, spec->get(p, 0))) return false;
    }
  }
  return true;
}

}  // namespace

Params runningParams(const Params& configured, ParamOrigins& origins) {
  origins.setupPending.clear();
  if (!origins.setUp()) {
    Params p = withSetupPendingLimits(configured, origins.setupPending);
    p.SetupBankFromBattery = bankSizeUnnamed(configured, origins);
    return p;
  }
  Params p = configured;
  p.SetupCeilingV = 0.0;  // set up: no ceiling, whatever set this came from
  p.SetupBankFromBattery = false;
  return p;
}

namespace {

std::string tomlValue(const ParamSpec& s, const Params& p) {
  if (!s.choices.empty()) return "\"" + std::string(choiceName(s, static_cast<int>(s.get(p, 0)))) + "\"";
  if (s.kind == ParamKind::Bool) return s.get(p, 0) != 0.0 ? "true" : "false";
  std::string v = formatParamValue(getParamValue(p, s));
  // A TOML float needs a decimal point or an exponent ("14" would be read
  // back as an integer, which the Float parameters accept anyway).
  return v;
}

std::string settingText(const SettingSpec& s, const Settings& st) {
  const SettingValue v = s.get(st);
  if (const auto* str = std::get_if<std::string>(&v)) {
    std::string out = "\"";
    for (char c : *str) {
      if (c == '"' || c == '\\') out += '\\';
      out += c;
    }
    return out + "\"";
  }
  if (const auto* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  if (const auto* d = std::get_if<double>(&v)) return formatNumber(*d);
  if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
  const auto& l = std::get<std::vector<std::int64_t>>(v);
  std::string out = "[";
  for (std::size_t k = 0; k < l.size(); ++k) out += (k ? ", " : "") + std::to_string(l[k]);
  return out + "]";
}

}  // namespace

std::string effectiveConfigText(const Settings& settings, const Params& p, const ParamOrigins& origins) {
  std::ostringstream o;
  o << "# Effective configuration of xregulatord: the file, the battery profile and the stored\n"
       "# dashboard overrides. Each value names its source.\n";
  if (!origins.setUp())
    o << "#\n# NOT SET UP: no battery type is chosen (BatteryProfile, in the file or on the set-up\n"
         "# page), so the regulator charges only within limits safe for every chemistry: "
      << setupPendingLimitsText(p) << ". Values marked '# not set up' are lowered to them.\n";
  std::string_view table;
  for (const auto& s : catalogue()) {
    if (tomlTableName(s.group) != table) {
      table = tomlTableName(s.group);
      o << "\n[" << table << "]\n";
    }
    o << s.name << " = " << tomlValue(s, p) << "  # " << toString(origins.of(s.name)) << "\n";
  }
  const Settings defaults{};
  for (std::string_view t : settingsTables()) {
    o << "\n[" << t << "]\n";
    for (const auto& s : settingsSchema()) {
      if (s.table != t) continue;
      const bool same = s.get(settings) == s.get(defaults);
      o << s.key << " = " << settingText(s, settings) << "  # " << (same ? "default" : "file") << "\n";
    }
  }
  return o.str();
}

}  // namespace xr
