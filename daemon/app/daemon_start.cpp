#include "app/daemon_start.h"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <exception>

#include "app/daemon_notices.h"
#include "app/effective_params.h"
#include "app/sim_wiring.h"
#include "config/battery_profiles.h"
#include "config/hardware_choices.h"
#include "config/setup_pending.h"
#include "store/ledger_check.h"

namespace xr::app {

namespace {

// The scenario (--sim), its [config] joining the file's layer. false: a bad
// scenario, said on stderr and in the journal.
bool loadScenario(const CliOptions& cli, Settings& settings, StartState& st) {
  try {
    st.scenario = cli.scenario ? sim::loadScenario(*cli.scenario) : sim::defaultScenario();
    sim::applyOverrides(st.fileParams, st.scenario->config, st.scenario->source);
    for (const auto& c : st.scenario->config) st.origins.file.insert(c.name);
    // A scenario's boat is set up unless it says set_up = false (param_sources.h).
    st.origins.assumeSetUp = cli.scenario.has_value() && st.scenario->set_up;
    applyScenarioWeather(*st.scenario, settings.integrations.weather);
    // A scenario's probe on the bank is its board's configured battery probe,
    // as its [config] is its file (the set-up page can then choose none).
    if (st.scenario->plant.battery.temp_sensor && settings.hardware.battery_temp_sensor.empty())
      settings.hardware.battery_temp_sensor = sim::kSimBatteryW1Id;
  } catch (const std::exception& e) {
    spdlog::critical("{}", e.what());
    std::fprintf(stderr, "xregulatord: %s\n", e.what());
    return false;
  }
  spdlog::info("scenario '{}' ({} s, seed {})", st.scenario->name, st.scenario->duration_s,
               cli.seed ? *cli.seed : st.scenario->seed);
  return true;
}

// The set-up page's hardware choices over the file's settings, before any
// device opens. A choice the file has since made impossible (the same
// interface for NMEA 2000, a Victron GX now enabled) is not used: the file's
// value runs, and the journal says why.
void layStoredHardwareChoices(StoreService& store, Settings& settings) {
  const HardwareChoices c = store.loadHardwareChoices();
  if (c == HardwareChoices{}) return;
  if (const auto errors = layHardwareChoices(settings, c); !errors.empty()) {
    for (const auto& [key, message] : errors)
      spdlog::error("set-up: the choice of {} is not used: {}; the file's value runs", key, message);
    return;
  }
  spdlog::info(
      "set-up: battery temperature probe '{}', BMS on CAN '{}', pulley ratio {} (the set-up page's choices "
      "over "
      "the file)",
      settings.hardware.battery_temp_sensor, settings.can.bms_interface,
      settings.hardware.frontend.pulley_ratio);
}

// Opens the state database (locked first: one daemon per database), restores
// the ledger and lays the stored dashboard settings over the file's.
void openStore(const std::string& dbPath, Settings& settings, StartState& st) {
  st.store = std::make_unique<StoreService>(dbPath, settings.store.checkpoint_interval_s);
  const OpenResult& o = st.store->openResult();
  if (const char* code = StoreService::alarmCode(o))
    spdlog::error("store: {}: {}", code, o.message);  // the line to look for (docs/operations.md)
  else
    spdlog::info("store: {} ({})", dbPath, o.message);
  if (auto saved = st.store->loadLedger()) {
    st.restored = saved->ledger;
    spdlog::info("store: ledger restored (saved for '{}')", saved->reason);
  }
  layStoredHardwareChoices(*st.store, settings);
  // An install from before "not set up" existed keeps charging as it did
  // (store/schema.cpp, v4).
  if (st.store->loadValue("set_up_before_upgrade")) st.origins.assumeSetUp = true;
  const OverrideResolution resolved = st.store->applyOverrides(st.fileParams, st.origins.file);
  for (const auto& d : resolved.dropped) spdlog::error("{}", d.text());
  std::string why;
  st.configured = withDashboardLayer(st.fileParams, resolved, st.origins, &why);
  if (!why.empty()) spdlog::error("{}", why);
}

// The health ledger checked like every stored value, against the capacity
// the regulator runs with (store/ledger_check.h): dropped with an event.
void checkRestoredLedger(StartState& st) {
  if (!st.restored || !st.store) return;
  const std::string why = dropImplausibleCapacity(*st.restored, st.configured.BatteryCapacity_Ah);
  if (why.empty()) return;
  spdlog::warn("store: {}", why);
  EventRecord e;
  e.tMs = unixMsNow();
  e.level = "warning";
  e.code = "LedgerDropped";
  e.reason = "NONE";
  e.message = why;
  st.store->appendRecord(e);
}

// Not set up: the file may not name a voltage target above the lowered set
// (refused like any bad file, as --check-config does); a stored dashboard
// value above it is lowered by the running layer, and said.
bool setupPendingTargetsFit(const StartState& st) {
  bool fit = true;
  for (const auto& e : checkSetupPendingTargets(st.configured)) {
    if (st.origins.dashboard.count(e.key)) {
      spdlog::error("stored dashboard setting {}: {}; lowered until set up", e.key, e.message);
    } else if (st.origins.file.count(e.key)) {
      spdlog::error("configuration: {}", e.message);
      fit = false;
    }
  }
  return fit;
}

}  // namespace

StartState loadStartState(const Config& config, const CliOptions& cli, Settings& settings) {
  StartState st;
  if (auto n = profileShadowNotice(config.params, config.fileParamNames); !n.empty()) spdlog::warn("{}", n);
  for (const auto& n : config.notices) spdlog::warn("{}", n);
  st.fileParams = config.params;
  st.origins.file = config.fileParamNames;
  // A bad scenario is bad input on the command line (exit 64, EX_USAGE), not
  // a bad configuration file (78).
  if (cli.sim && !loadScenario(cli, settings, st)) {
    st.exitCode = kExitUsage;
    return st;
  }
  st.fileParams = applyLayers(st.fileParams, st.origins);  // the profile under the file and [config]
  if (st.scenario && !scenarioConfigFits(st.fileParams, st.scenario->source)) {
    st.exitCode = kExitUsage;
    return st;
  }
  st.configured = st.fileParams;
  st.fileSettings = settings;
  const std::string dbPath = cli.stateDb.value_or(cli.sim ? std::string() : settings.store.path);
  if (!dbPath.empty()) {
    st.stateLock = lockStateDatabase(dbPath);
    if (!st.stateLock) {
      st.exitCode = kExitTempFail;  // before any output is driven: the field was never enabled by us
      return st;
    }
    openStore(dbPath, settings, st);
    checkRestoredLedger(st);
  }
  if (!st.origins.setUp() && !setupPendingTargetsFit(st)) {
    st.exitCode = kExitConfig;  // before any output is driven, as every refused file
    return st;
  }
  st.running = runningParams(st.configured, st.origins);
  if (!st.origins.setUp())
    spdlog::warn(
        "not set up: no battery type is chosen (BatteryProfile, in the file or on the set-up page); "
        "charging only within limits safe for every chemistry: {}",
        setupPendingLimitsText(st.running));
  return st;
}

}  // namespace xr::app
