#pragma once
// The first step of Daemon::run (docs/architecture.md "Start-up"): the
// parameters, layer by layer (file, a scenario's [config], the battery
// profile, the stored dashboard settings, the "not set up" limits), with the
// state database opened and locked on the way. Nothing here drives an output.
#include <memory>
#include <optional>
#include <string>

#include "app/cli.h"
#include "app/store_service.h"
#include "battery/ledger.h"
#include "config/param_sources.h"
#include "config/settings.h"
#include "drivers/sim/scenario.h"
#include "runtime/wall_clock.h"
#include "store/state_lock.h"

namespace xr::app {

struct StartState {
  Params fileParams;      // file + [config] + profile: what a dropped dashboard value falls back to
  Params configured;      // + the stored dashboard settings: what a PATCH starts from
  Params running;         // + the "not set up" limits: what the regulator runs with
  Settings fileSettings;  // the file's (and a scenario's board): what a set-up choice lies over
  ParamOrigins origins;
  std::optional<sim::Scenario> scenario;  // --sim only
  std::unique_ptr<StateLock> stateLock;   // held until exit (store/state_lock.h)
  std::unique_ptr<StoreService> store;    // null without a state database
  std::optional<BatteryLedger> restored;  // the ledger saved by the last run
  rt::WallClock clock;                    // the one wall clock: simulated in --sim (Daemon::run)
  int exitCode = 0;                       // non-zero: stop with it, nothing was started
};

// settings: a scenario's [weather] may add to it.
StartState loadStartState(const Config& config, const CliOptions& cli, Settings& settings);

}  // namespace xr::app
