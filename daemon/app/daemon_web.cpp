#include "app/daemon_web.h"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <exception>
#include <filesystem>

#include "app/daemon_notices.h"
#include "app/pair_cli.h"
#include "app/store_auth.h"
#include "config/web_checks.h"
#include "web/server/on_board.h"

namespace xr::app {

namespace {

WebApiContext apiContext(const CliOptions& cli, const DaemonWebInputs& in) {
  WebApiContext ctx;
  ctx.handoffs = in.handoffs;
  ctx.fileParams = in.start->fileParams;
  ctx.origins = in.start->origins;
  in.handoffs->setUp.store(ctx.origins.setUp());
  ctx.configured = in.start->configured;
  ctx.store = in.start->store.get();
  ctx.events = in.recent;
  ctx.sim = cli.sim;
  ctx.controlPeriodUs = in.settings->runtime.control_period_us;
  ctx.lastHeartbeatWallMs = in.lastHeartbeatWallMs;
  ctx.fieldSafeFault = in.fieldSafeFault;
  ctx.integrations = in.integrations;
  ctx.fileSettings = in.start->fileSettings;
  ctx.runningSettings = *in.settings;
  ctx.w1Root = in.w1Root;
  ctx.update = in.update;
  return ctx;
}

// [web] www_root, else the first folder with an index.html: the build tree,
// the source tree, then the package's.
std::string wwwRoot(const std::string& configured) {
  if (!configured.empty()) return configured;
  for (const char* p : {"web/www/dist", "web/www", XR_SOURCE_DIR "/web/www/dist", XR_SOURCE_DIR "/web/www",
                        "/usr/share/xregulator/www"}) {
    if (std::filesystem::exists(std::string(p) + "/index.html")) return p;
  }
  return {};
}

}  // namespace

DaemonWeb startWeb(const CliOptions& cli, const DaemonWebInputs& in) {
  DaemonWeb web;
  if (!cli.http && cli.sim) return web;
  const Settings& settings = *in.settings;
  StoreService* store = in.start->store.get();
  web.api = std::make_unique<WebApi>(apiContext(cli, in));
  auto opts = web::WebServerOptions::fromSettings(settings.web, settings.web.token);
  opts.www_root = wwwRoot(opts.www_root);
  // --http was checked with the command line, before any device opened (cli.cpp).
  if (cli.http && !web::parseListenAddress(*cli.http, opts))
    spdlog::error("--http {}: not understood here; serving on [web] listen instead", *cli.http);
  try {
    if (opts.token.empty()) opts.token = store ? store->token() : web::generateToken();
    if (store) opts.auth_store = std::make_shared<StoreAuthStore>(*store);
    web.server = std::make_unique<web::WebServer>(*web.api, opts);
    web.server->start();
    startPairing(*web.server, store);
    spdlog::info("dashboard at http://{}/ (www root '{}')",
                 web::hostPortText(opts.listen, web.server->port()), opts.www_root);
    logEveryInterface(opts.listen, web.server->port());
    logTokenHint(settings.web.token.empty(), store != nullptr, opts.token,
                 cli.stateDb.value_or(settings.store.path));
    if (cli.config)
      if (auto w = tokenFileWarning(*cli.config, settings.web.token); !w.empty()) spdlog::warn("{}", w);
  } catch (const std::exception& e) {
    web.server.reset();
    web.down = true;
    spdlog::critical("web server cannot start on {}: {}: the regulator runs WITHOUT the dashboard and API",
                     web::hostPortText(opts.listen, opts.port), e.what());
    std::fprintf(stderr, "xregulatord: web server: %s: running without it\n", e.what());
  }
  return web;
}

}  // namespace xr::app
