#pragma once
// The non-real-time services around the control thread (docs/architecture.md
// "Threads"): the event pump and its sinks, the telemetry CSV writer, the
// boat's network, the CAN thread on a board, and the dashboard. Started in
// that order; stop() — also the destructor, so every way out of Daemon::run
// takes it — stops the web server, the pump and the CSV writer in turn.
#include <atomic>
#include <cstdint>
#include <fstream>
#include <memory>

#include "app/can_wiring.h"
#include "app/csv_writer.h"
#include "app/daemon_rig.h"
#include "app/daemon_start.h"
#include "app/daemon_web.h"
#include "app/status_source.h"
#include "app/update_watch.h"
#include "integrations/integrations_service.h"
#include "runtime/event_pump.h"

namespace xr::app {

class DaemonServices {
 public:
  // `csv` (--telemetry-csv) and `canLog` (--can-log) were opened before the
  // rig; either may be null.
  DaemonServices(const CliOptions& cli, const StartState& start, const Settings& settings,
                 rt::Handoffs& handoffs, DaemonRig& rig, std::unique_ptr<CsvWriter> csv,
                 std::unique_ptr<std::ofstream> canLog);
  ~DaemonServices() { stop(); }
  DaemonServices(const DaemonServices&) = delete;
  DaemonServices& operator=(const DaemonServices&) = delete;

  void stop();

  WebApi* api() { return web_.api.get(); }
  web::WebServer* server() { return web_.server.get(); }
  bool webDown() const { return web_.down; }
  // Written by the supervisor, read by the API's health answer.
  std::atomic<std::int64_t>& lastHeartbeatWallMs() { return lastHeartbeatWallMs_; }
  std::atomic<bool>& outputsFault() { return outputsFault_; }
  UpdateWatch& updateWatch() { return update_; }

 private:
  RecentEvents recent_;
  integrations::IncidentFeed incidents_;  // before pump_: its sink fills it
  rt::EventPump pump_;
  std::unique_ptr<CsvWriter> csv_;
  std::unique_ptr<integrations::IntegrationsService> integrations_;
  std::unique_ptr<CanThread> can_;
  std::atomic<std::int64_t> lastHeartbeatWallMs_{0};
  std::atomic<bool> outputsFault_{false};
  UpdateWatch update_;  // before web_: the API reads it
  DaemonWeb web_;
};

}  // namespace xr::app
