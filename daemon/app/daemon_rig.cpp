#include "app/daemon_rig.h"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <exception>

#include "runtime/fatal_guard.h"

namespace xr::app {

std::unique_ptr<DaemonRig> DaemonRig::open(const StartState& start, const Settings& settings,
                                           const CliOptions& cli, rt::Handoffs& handoffs,
                                           std::unique_ptr<std::ofstream>& canLog) {
  std::unique_ptr<DaemonRig> rig(new DaemonRig());
  try {
    if (cli.sim) {
      rig->sim_ = std::make_unique<SimWiring>(*start.scenario, settings, cli, std::move(canLog),
                                              start.fileSettings.hardware.frontend.pulley_ratio);
      rig->sim_->attach(handoffs);
      if (auto* m = rig->sim_->mirror()) m->registerFatalAction();
    } else {
      rig->board_ = std::make_unique<BoardRig>(settings);
      rig->board_->attach(handoffs);
      rig->board_->registerFatalActions();
      if (!rig->board_->watchdogWarning().empty()) spdlog::warn("{}", rig->board_->watchdogWarning());
      if (!rig->board_->readyLineWarning().empty()) spdlog::warn("{}", rig->board_->readyLineWarning());
      if (!rig->board_->pairingButtonWarning().empty())
        spdlog::warn("{}", rig->board_->pairingButtonWarning());
    }
  } catch (const std::exception& e) {
    rt::fatal::driveSafeNow();
    spdlog::critical("hardware setup failed: {}", e.what());
    std::fprintf(stderr, "xregulatord: %s\n", e.what());
    return nullptr;
  }
  return rig;
}

std::function<TimeNs(TimeNs)> DaemonRig::wallDeadlineOf() {
  if (sim_) return sim_->wallDeadlineOf();
  return [](TimeNs t) { return t; };
}

void DaemonRig::startSensors(double bovlVolts) {
  const auto r = sim_ ? sim_->startSensors(bovlVolts) : board_->startSensors(bovlVolts);
  if (r.inaError) spdlog::error("INA228 not answering at start (errno {}): will re-detect", r.inaError);
  if (r.adsError) spdlog::error("ADS1115 not answering at start (errno {}): will re-detect", r.adsError);
}

std::string DaemonRig::w1Root(const Settings& settings) const {
  return sim_ ? sim_->w1Root() : settings.hardware.w1_root;
}

void DaemonRig::markCleanStop() {
  if (auto* wd = devices().watchdog) wd->closeClean();
  if (sim_ && sim_->mirror()) sim_->mirror()->markStopped();
}

}  // namespace xr::app
