#pragma once
// The dashboard and API of the running daemon (docs/dashboard.md): built from
// [web] and --http once the control cycle exists. The dashboard is a
// convenience: when its server cannot start the regulator runs on without it,
// loudly (docs/security.md).
#include <atomic>
#include <cstdint>
#include <memory>

#include "app/cli.h"
#include "app/daemon_start.h"
#include "app/update_watch.h"
#include "app/web_api.h"
#include "web/server/web_server.h"

namespace xr::app {

struct DaemonWeb {
  std::unique_ptr<WebApi> api;
  std::unique_ptr<web::WebServer> server;
  bool down = false;  // wanted, but its server could not start
};

// What the API reads that the daemon owns.
struct DaemonWebInputs {
  const StartState* start = nullptr;
  const Settings* settings = nullptr;  // the running settings
  rt::Handoffs* handoffs = nullptr;
  RecentEvents* recent = nullptr;
  std::function<std::vector<web::IntegrationState>()> integrations;
  std::string w1Root;
  std::atomic<std::int64_t>* lastHeartbeatWallMs = nullptr;
  std::atomic<bool>* fieldSafeFault = nullptr;
  const UpdateWatch* update = nullptr;  // version, channel, install time, a pending update
};

// Empty when --sim runs without --http (a headless run); a board always serves.
DaemonWeb startWeb(const CliOptions& cli, const DaemonWebInputs& in);

}  // namespace xr::app
