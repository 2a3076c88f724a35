#include "app/config_check.h"

#include <filesystem>
#include <ostream>

#include "app/effective_params.h"
#include "app/stored_overrides.h"
#include "config/battery_profiles.h"
#include "config/config.h"
#include "config/param_sources.h"
#include "config/setup_pending.h"
#include "config/web_checks.h"

namespace xr::app {

namespace {

// Not set up (no BatteryProfile in the file, none chosen on the set-up page,
// not an install from before): the file may not name a voltage target above
// the lowered set; the daemon refuses it at start too (daemon_start.cpp).
// No bank size named: the class is read from the battery at start
// (docs/configuration.md "Not set up"), and the limits above are its 12 V ones.
std::string bankReadNote(const Params& p, const NameSet& fileNames) {
  ParamOrigins origins;
  origins.file = fileNames;
  if (!runningParams(p, origins).SetupBankFromBattery) return "";
  return "; per 12 V of bank: the bank's size is read from the battery at start";
}

bool setupPendingTargetsFit(const std::string& file, const Config& config, const std::string& db,
                            const std::vector<OverrideRow>& rows, std::ostream& err) {
  if (config.fileParamNames.count("BatteryProfile")) return true;
  for (const auto& row : rows)
    if (row.name == "BatteryProfile") return true;
  if (!db.empty() && setUpBeforeUpgradeReadOnly(db)) return true;
  bool fit = true;
  for (const auto& e : checkSetupPendingTargets(config.params)) {
    if (!config.fileParamNames.count(e.key)) continue;
    bool stored = false;  // the dashboard's value replaces the file's
    for (const auto& row : rows) stored = stored || row.name == e.key;
    if (stored) continue;
    const ParamSpec* s = findParam(e.key);
    err << ConfigError{file, 0, 0, std::string(tomlTableName(s->group)) + "." + e.key, e.message}.toString()
        << "\n";
    fit = false;
  }
  return fit;
}

}  // namespace

int checkConfigAndState(const std::string& configPath, const std::optional<std::string>& stateDb,
                        std::ostream& out, std::ostream& err) {
  const int rc = checkConfigMain(configPath, out, err);
  if (rc != 0) return rc;
  const LoadResult r = loadConfigFile(configPath);
  if (!r.ok()) return kExitConfig;  // changed between the two reads
  if (auto w = tokenFileWarning(configPath, r.config->settings.web.token); !w.empty())
    out << "warning: " << w << "\n";
  if (auto n = profileShadowNotice(r.config->params, r.config->fileParamNames); !n.empty())
    out << "warning: " << n << "\n";
  for (const auto& n : r.config->notices) out << "warning: " << n << "\n";
  // Not an error: the set-up page may still choose the battery.
  if (!r.config->fileParamNames.count("BatteryProfile"))
    out << "note: no BatteryProfile in this file; unless the set-up page chose one, the regulator is not set "
           "up and charges only within limits safe for every chemistry ("
        << setupPendingLimitsText(r.config->params) << ")"
        << bankReadNote(r.config->params, r.config->fileParamNames) << "\n";

  const std::string db = stateDb.value_or(r.config->settings.store.path);
  std::error_code ec;
  const bool haveDb = !db.empty() && std::filesystem::exists(db, ec);
  std::string why;
  const auto rows = haveDb ? readOverridesReadOnly(db, &why) : std::vector<OverrideRow>{};
  if (!setupPendingTargetsFit(configPath, *r.config, haveDb ? db : std::string(), rows, err))
    return kExitConfig;
  if (!haveDb) return 0;  // first start: nothing stored yet
  if (!why.empty()) {
    out << "warning: " << why << " (the stored dashboard settings were not checked)\n";
    return 0;
  }
  const OverrideResolution res = resolveStoredOverrides(r.config->params, r.config->fileParamNames, rows);
  for (const auto& d : res.dropped) out << "warning: " << db << ": " << d.text() << " (at the next start)\n";
  out << db << ": " << rows.size() - res.dropped.size() << " stored dashboard setting"
      << (rows.size() - res.dropped.size() == 1 ? "" : "s") << " fit the configuration";
  if (!res.dropped.empty()) out << ", " << res.dropped.size() << " will be dropped";
  out << "\n";
  return 0;
}

int printConfigMain(const std::optional<std::string>& configPath, const std::optional<std::string>& stateDb,
                    std::ostream& out, std::ostream& err) {
  Config config;
  if (configPath) {
    LoadResult r = loadConfigFile(*configPath);
    if (!r.ok()) {
      for (const auto& e : r.errors) err << e.toString() << "\n";
      return kExitConfig;
    }
    config = std::move(*r.config);
  }
  ParamOrigins origins;
  origins.file = config.fileParamNames;
  Params params = applyLayers(config.params, origins);
  const std::string db = stateDb.value_or(configPath ? config.settings.store.path : std::string());
  std::error_code ec;
  if (!db.empty() && std::filesystem::exists(db, ec)) {
    origins.assumeSetUp = setUpBeforeUpgradeReadOnly(db);  // as the daemon will (daemon_start.cpp)
    // The set-up page's probe and BMS choices, as the next start lays them.
    const HardwareChoices choices = hardwareChoicesReadOnly(db);
    if (choices != HardwareChoices{}) {
      const auto bad = layHardwareChoices(config.settings, choices);
      for (const auto& [key, message] : bad)
        err << "warning: the set-up page's choice of " << key << " will not be used: " << message << "\n";
      // A choice not used leaves the file's value, which needs no note.
      for (const auto& [key, made] : {std::pair{"battery_temp_sensor", choices.batteryTempSensor.has_value()},
                                      std::pair{"bms_interface", choices.bmsInterface.has_value()},
                                      std::pair{"pulley_ratio", choices.pulleyRatio.has_value()}})
        if (made && bad.empty())
          err << "note: " << key << " below is the set-up page's choice, not the file's\n";
    }
    std::string why;
    const auto rows = readOverridesReadOnly(db, &why);
    if (!why.empty()) {
      err << "warning: " << why << " (stored dashboard settings not shown)\n";
    } else {
      const OverrideResolution res = resolveStoredOverrides(params, origins.file, rows);
      for (const auto& d : res.dropped) err << "warning: " << d.text() << "\n";
      std::string setAside;
      params = withDashboardLayer(params, res, origins, &setAside);
      if (!setAside.empty()) err << "warning: " << setAside << "\n";
    }
  }
  params = runningParams(params, origins);
  out << effectiveConfigText(config.settings, params, origins);
  return 0;
}

int printTokenMain(const std::optional<std::string>& configPath, const std::optional<std::string>& stateDb,
                   std::ostream& out, std::ostream& err) {
  std::string db;
  if (stateDb) {
    db = *stateDb;
  } else {
    const LoadResult r = loadConfigFile(*configPath);
    if (!r.ok()) {
      for (const auto& e : r.errors) err << e.toString() << "\n";
      return 1;
    }
    if (!r.config->settings.web.token.empty()) {
      out << r.config->settings.web.token << "\n";
      return 0;
    }
    db = r.config->settings.store.path;
  }
  std::string why;
  const std::string token = readTokenReadOnly(db, &why);
  if (token.empty()) {
    err << "xregulatord: "
        << (why.empty() ? db + ": no token stored yet (the daemon makes one at first start)" : why) << "\n";
    return 1;
  }
  out << token << "\n";
  return 0;
}

}  // namespace xr::app
