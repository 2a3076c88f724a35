#include "app/daemon.h"

#include <signal.h>
#include <spdlog/spdlog.h>
#include <systemd/sd-daemon.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>

#include "app/board_rig.h"
#include "app/can_wiring.h"
#include "app/csv_writer.h"
#include "app/daemon_notices.h"
#include "app/daemon_start.h"
#include "app/integrations_wiring.h"
#include "app/pair_cli.h"
#include "app/sim_wiring.h"
#include "app/status_source.h"
#include "app/stop_signal.h"
#include "app/store_auth.h"
#include "app/store_service.h"
#include "app/thread_names.h"
#include "app/web_api.h"
#include "config/battery_profiles.h"
#include "config/config.h"
#include "config/web_checks.h"
#include "control/regulator.h"
#include "drivers/sim/scenario.h"
#include "logging/logging.h"
#include "params/derived.h"
#include "runtime/control_loop.h"
#include "runtime/event_pump.h"
#include "runtime/fatal_guard.h"
#include "runtime/regulator_core.h"
#include "runtime/rt_setup.h"
#include "runtime/signals.h"
#include "store/state_lock.h"
#include "web/server/web_server.h"

namespace xr::app {

namespace {

double wallSecondsNow() { return static_cast<double>(unixMsNow()) / 1000.0; }

// --can-log's file; false: it cannot be created, said on stderr and in the journal.
bool openCanLogOrSay(const std::string& path, std::unique_ptr<std::ofstream>& out) {
  try {
    out = openCanLog(path);
    return true;
  } catch (const std::exception& e) {
    spdlog::critical("{}", e.what());
    std::fprintf(stderr, "xregulatord: %s\n", e.what());
    return false;
  }
}

}  // namespace

int Daemon::run() {
  Settings settings = config_.settings;  // a scenario's [weather] may add to it
  const auto kernel = rt::detectPreemptRt();
  spdlog::info("xregulatord {} starting ({}), kernel {}: PREEMPT_RT {} ({})", XR_VERSION_STRING,
               cli_.sim ? "simulation" : "board", kernel.release, kernel.preemptRt ? "yes" : "no",
               kernel.how);

  // ---- parameters and the state database (daemon_start.h) ----
  StartState start = loadStartState(config_, cli_, settings);
  if (start.exitCode != 0) return start.exitCode;
  std::unique_ptr<StoreService>& store = start.store;
  std::optional<sim::Scenario>& scenario = start.scenario;
  const Params& params = start.running;

  // ---- the core and the hand-offs ----
  Regulator regulator(params);
  if (start.restored) regulator.restoreLedger(*start.restored);
  rt::RegulatorCore core(regulator);
  auto handoffs = std::make_unique<rt::Handoffs>(params);

  // --can-log, opened before anything runs: an output file that cannot be
  // created stops the daemon at start, like --telemetry-csv.
  std::unique_ptr<std::ofstream> canLog;
  if (cli_.canLog && !openCanLogOrSay(*cli_.canLog, canLog)) return kExitConfig;

  // ---- the rig ----
  std::unique_ptr<SimWiring> simRig;
  std::unique_ptr<BoardRig> boardRig;
  rt::CycleDevices devices;
  Clock* loopClock = nullptr;
  rt::MonotonicClock* wall = nullptr;
  std::function<TimeNs(TimeNs)> wallDeadlineOf;
  try {
    if (cli_.sim) {
      simRig = std::make_unique<SimWiring>(*scenario, settings, cli_, std::move(canLog),
                                           start.fileSettings.hardware.frontend.pulley_ratio);
      simRig->attach(*handoffs);
      devices = simRig->devices();
      loopClock = &simRig->loopClock();
      wall = &simRig->wall();
      wallDeadlineOf = simRig->wallDeadlineOf();
      if (auto* m = simRig->mirror()) m->registerFatalAction();
    } else {
      boardRig = std::make_unique<BoardRig>(settings);
      boardRig->attach(*handoffs);
      devices = boardRig->devices();
      loopClock = &boardRig->loopClock();
      wall = &boardRig->wall();
      wallDeadlineOf = [](TimeNs t) { return t; };
      boardRig->registerFatalActions();
      if (!boardRig->watchdogWarning().empty()) spdlog::warn("{}", boardRig->watchdogWarning());
      if (!boardRig->readyLineWarning().empty()) spdlog::warn("{}", boardRig->readyLineWarning());
    }
  } catch (const std::exception& e) {
    rt::fatal::driveSafeNow();
    spdlog::critical("hardware setup failed: {}", e.what());
    std::fprintf(stderr, "xregulatord: %s\n", e.what());
    return kExitUnavailable;
  }
  rt::fatal::install();

  rt::LoopStats stats;
  rt::CycleConfig cycleCfg;
  cycleCfg.rowPeriod = cli_.telemetryCsv ? fromSec(1.0 / cli_.telemetryRateHz) : 0;
  cycleCfg.blockOnFullRows = cli_.sim && cli_.speed <= 0.0;
  if (cli_.sim && cli_.speed <= 0.0) cycleCfg.thinForUnpacedRun();
  cycleCfg.rpmFromN2k =
      settings.can.RpmSource == "n2k";  // engine speed from the CAN service (docs/integrations.md)
  rt::ControlCycle cycle(core, devices, *handoffs, stats, *wall, cycleCfg);
  cycle.driveSafeState();  // field known LOW before anything runs

  const auto sensorsStart = simRig ? simRig->startSensors(voltageHardwareLimit(params))
                                   : boardRig->startSensors(voltageHardwareLimit(params));
  if (sensorsStart.inaError)
    spdlog::error("INA228 not answering at start (errno {}): will re-detect", sensorsStart.inaError);
  if (sensorsStart.adsError)
    spdlog::error("ADS1115 not answering at start (errno {}): will re-detect", sensorsStart.adsError);

  // ---- non-RT services ----
  RecentEvents recent;
  rt::EventPump pump(handoffs->events);
  pump.addSource(handoffs->sideEvents);  // the CAN thread's events (docs/integrations.md)
  pump.addSink([](const Event& e) { logEvent(e); });
  pump.addSink([&recent](const Event& e) { recent.add(e, wallSecondsNow(), describe(e)); });
  if (store) pump.addSink([&store](const Event& e) { store->appendEvent(e); });
  pump.start();

  std::unique_ptr<CsvWriter> csv;
  if (cli_.telemetryCsv) {
    try {
      csv = std::make_unique<CsvWriter>(*cli_.telemetryCsv, *handoffs, cli_.sim);
    } catch (const std::exception& e) {
      spdlog::critical("{}", e.what());
      std::fprintf(stderr, "xregulatord: %s\n", e.what());
      pump.stop();
      return kExitConfig;
    }
    csv->start();
  }

  // The boat's network (docs/integrations.md): its own thread, reading the snapshot only.
  const auto integrations = startIntegrations(settings, *handoffs, store.get());
  // CAN (docs/integrations.md): on a board the xr-can thread; the sim rig runs its own.
  const auto canThread =
      boardRig ? startCanThread(settings, *handoffs, boardRig->loopClock(), std::move(canLog)) : nullptr;

  std::atomic<std::int64_t> lastHeartbeatWallMs{0};
  std::atomic<bool> outputsFault{false};
  std::unique_ptr<WebApi> api;
  std::unique_ptr<web::WebServer> server;
  const bool wantWeb = cli_.http.has_value() || !cli_.sim;
  bool webDown = false;
  if (wantWeb) {
    WebApiContext ctx;
    ctx.handoffs = handoffs.get();
    ctx.fileParams = start.fileParams;
    ctx.origins = start.origins;
    ctx.configured = start.configured;
    ctx.store = store.get();
    ctx.events = &recent;
    ctx.sim = cli_.sim;
    ctx.controlPeriodUs = settings.runtime.control_period_us;
    ctx.lastHeartbeatWallMs = &lastHeartbeatWallMs;
    ctx.fieldSafeFault = &outputsFault;
    ctx.integrations = integrationsView(integrations.get());
    ctx.fileSettings = start.fileSettings;
    ctx.runningSettings = settings;
    ctx.w1Root = simRig ? simRig->w1Root() : settings.hardware.w1_root;
    api = std::make_unique<WebApi>(ctx);
    auto opts = web::WebServerOptions::fromSettings(settings.web, settings.web.token);
    if (opts.www_root.empty()) {
      for (const char* p : {"web/www/dist", "web/www", XR_SOURCE_DIR "/web/www/dist",
                            XR_SOURCE_DIR "/web/www", "/usr/share/xregulator/www"}) {
        if (std::filesystem::exists(std::string(p) + "/index.html")) {
          opts.www_root = p;
          break;
        }
      }
    }
    if (cli_.http && !web::parseListenAddress(*cli_.http, opts)) {
      std::fprintf(stderr, "xregulatord: --http: expected ADDR:PORT, got '%s'\n", cli_.http->c_str());
      pump.stop();
      if (csv) csv->stop();
      return kExitUsage;
    }
    try {
      if (opts.token.empty()) opts.token = store ? store->token() : web::generateToken();
      if (store) opts.auth_store = std::make_shared<StoreAuthStore>(*store);
      server = std::make_unique<web::WebServer>(*api, opts);
      server->start();
      startPairing(*server, store.get());
      spdlog::info("dashboard at http://{}:{}/ (www root '{}')", opts.listen, server->port(), opts.www_root);
      logEveryInterface(opts.listen, server->port());
      logTokenHint(settings.web.token.empty(), store != nullptr, opts.token,
                   cli_.stateDb.value_or(settings.store.path));
      if (cli_.config)
        if (auto w = tokenFileWarning(*cli_.config, settings.web.token); !w.empty()) spdlog::warn("{}", w);
    } catch (const std::exception& e) {
      // The dashboard is a convenience; the regulator runs without it
      // (docs/security.md). Loud in the journal, on stderr and in the status.
      server.reset();
      webDown = true;
      spdlog::critical(
          "web server cannot start on {}:{}: {}: the regulator runs WITHOUT the dashboard and API",
          opts.listen, opts.port, e.what());
      std::fprintf(stderr, "xregulatord: web server: %s: running without it\n", e.what());
    }
  }

  // ---- the control thread ----
  rt::LoopConfig loopCfg;
  loopCfg.period = fromUs(settings.runtime.control_period_us);
  if (cli_.durationS)
    loopCfg.duration = fromSec(*cli_.durationS);
  else if (cli_.sim && cli_.speed <= 0.0)
    loopCfg.duration = fromSec(scenario->duration_s);
  loopCfg.wallDeadlineOf = wallDeadlineOf;
  loopCfg.wall = wall;
  // Real deadlines only: its reads are system calls, no overrun can happen at
  // --speed max (docs/performance.md "Simulator speed").
  if (!cli_.sim || cli_.speed > 0.0) loopCfg.cpuTime = [] { return rt::threadCpuTime(); };
  rt::ControlLoop loop(cycle, *loopClock, stats, loopCfg);

  std::atomic<bool> controlFailed{false};
  std::string controlError;
  const bool realtime = !cli_.sim || cli_.speed > 0.0;
  rt::RtSetupReport rtReport;
  std::atomic<bool> rtReady{false};
  std::thread control([&] {
    rtReport = rt::setupRealtimeThread(settings.runtime, "xr-control", realtime);
    rtReady = true;
    rt::fatal::installAltStackForThisThread();
    try {
      loop.run();
    } catch (const std::exception& e) {
      controlError = e.what();
      controlFailed = true;
    } catch (...) {
      controlError = "unknown exception";
      controlFailed = true;
    }
    if (controlFailed) {
      cycle.driveSafeState();
      rt::fatal::driveSafeNow();
    }
  });
  while (!rtReady) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  spdlog::info("control thread: {} period {} us", rtReport.summary(), settings.runtime.control_period_us);
  for (const auto& w : rtReport.warnings) spdlog::warn("control thread: {}", w);

  sd_notify(0, "READY=1\nSTATUS=control loop running, field enable LOW until the regulator enables it");

  // ---- supervisor (this thread): signals, sd_notify, stats, store ----
  const sigset_t waited = rt::signals::waitedSet();
  int exitCode = 0;
  std::uint64_t lastBeat = 0;
  auto lastStatsLog = std::chrono::steady_clock::now();
  auto lastHousekeeping = lastStatsLog;
  bool stopRequested = false;
  bool edgeFallbackLogged = false;
  PresencePairing presence;  // the ignition turned off-on-off-on opens pairing (docs/security.md)
  try {
    while (!loop.finished() && !controlFailed) {
      timespec ts{0, 100'000'000};
      const int sig = sigtimedwait(&waited, nullptr, &ts);
      if (sig > 0) handleSignal(sig, loop, stopRequested, exitCode);
      const auto now = std::chrono::steady_clock::now();
      presence.poll(*handoffs, server.get(), api.get());
      const std::uint64_t beat = loop.heartbeat();
      if (beat != lastBeat) {
        lastBeat = beat;
        lastHeartbeatWallMs = unixMsNow();
        sd_notify(0, "WATCHDOG=1");  // only while the control thread ticks
      }
      if (cli_.testFault == TestFault::Throw && simRig) {
        const rt::RuntimeSnapshot s = handoffs->latest();
        if (s.tick > 0 && toSec(s.telemetry.now - s.start) >= cli_.testFaultAtS)
          throw std::runtime_error("test fault: exception on the main thread");
      }
      if (now - lastHousekeeping >= std::chrono::seconds(1)) {
        lastHousekeeping = now;
        const rt::RuntimeSnapshot s = handoffs->latest();
        outputsFault = s.health.outputWriteErrors > 0 && !s.telemetry.field_enable && s.health.stopping;
        sd_notifyf(0, "STATUS=%s %s SoC %.0f%% duty %.1f%%%s",
                   std::string(toString(s.telemetry.mode)).c_str(),
                   std::string(toString(s.telemetry.stage)).c_str(), s.telemetry.soc_pct,
                   s.telemetry.duty_pct, webDown ? " (web server DOWN, see the journal)" : "");
        if (store) store->housekeeping(s, handoffs->ledger.load(), s.tick > 100);
        if (api) api->flushPatchLog(now);
        if (s.health.adsEdgeFallback && !edgeFallbackLogged) {
          edgeFallbackLogged = true;
          spdlog::error(
              "ADS1115 ALERT/RDY: no conversion-ready edges on GPIO line {}: single-shot pacing instead (CH1 "
              "~200 Hz). Wire ALERT/RDY to that line (10 kOhm pull-up) or set ads_alert_rdy_line = -1",
              settings.hardware.ads_alert_rdy_line);
        }
      }
      if (now - lastStatsLog >= std::chrono::minutes(1)) {
        lastStatsLog = now;
        const rt::RuntimeSnapshot s = handoffs->latest();
        logLoopStats(s.loop, s.health);
      }
    }
  } catch (const std::exception& e) {
    // Safe state first, then tell.
    rt::fatal::driveSafeNow();
    loop.requestAbort();
    spdlog::critical("fatal: {}: field enable LOW, duty 0", e.what());
    exitCode = kExitSoftware;
    control.join();
    cycle.driveSafeState();
    rt::fatal::driveSafeNow();  // the last write wins: the mirror says via=fatal
    if (server) server->stop();
    pump.stop();
    if (csv) csv->stop();
    return exitCode;
  }
  control.join();

  if (controlFailed) {
    spdlog::critical("control thread failed: {}: field enable LOW, duty 0", controlError);
    exitCode = kExitSoftware;
  } else {
    // Clean stop: the field is off; only now may the watchdog be disarmed.
    if (devices.watchdog) devices.watchdog->closeClean();
    if (simRig && simRig->mirror()) simRig->mirror()->markStopped();
    spdlog::info("stopped cleanly: field enable LOW, duty 0");
  }
  const rt::RuntimeSnapshot last = handoffs->latest();
  // The control thread has ended: its statistics can be read directly (the
  // published summary is refreshed only every 64 ticks).
  logLoopStats(stats.summary(), cycle.health());
  if (server) server->stop();
  pump.stop();
  if (csv) csv->stop();
  if (store) store->stop(handoffs->ledger.load(), last.tick > 100);
  return exitCode;
}

}  // namespace xr::app
