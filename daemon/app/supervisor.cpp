#include "app/supervisor.h"

#include <signal.h>
#include <spdlog/spdlog.h>
#include <systemd/sd-daemon.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "app/daemon_notices.h"
#include "app/stop_signal.h"
#include "runtime/signals.h"

namespace xr::app {

int Supervisor::run() {
  const sigset_t waited = rt::signals::waitedSet();
  int exitCode = 0;
  bool stopRequested = false;
  auto lastStatsLog = std::chrono::steady_clock::now();
  auto lastHousekeeping = lastStatsLog;
  while (!loop_.finished() && !control_.failed()) {
    timespec ts{0, 100'000'000};
    const int sig = sigtimedwait(&waited, nullptr, &ts);
    if (sig > 0) handleSignal(sig, loop_, stopRequested, exitCode);
    const auto now = std::chrono::steady_clock::now();
    presence_.poll(handoffs_, services_.server(), services_.api());
    pollPairingButton();
    feedWatchdog();
    throwTestFault();
    if (now - lastHousekeeping >= std::chrono::seconds(1)) {
      lastHousekeeping = now;
      if (everySecond() && !stopRequested) {
        // The update watch's stop: the same controlled ramp as SIGTERM, then
        // exit 75 so that systemd (Restart=on-failure) starts the new version.
        sd_notify(0, "STOPPING=1\nSTATUS=stopping: an installed update starts now (engine stopped)");
        loop_.requestStop();
        stopRequested = true;
        exitCode = kExitTempFail;
      }
      if (auto* api = services_.api()) api->flushPatchLog(now);
    }
    if (now - lastStatsLog >= std::chrono::minutes(1)) {
      lastStatsLog = now;
      everyMinute();
    }
  }
  return exitCode;
}

// The button's edges carry the loop clock's time (drivers/hal/button.h): the
// latest tick's time is "now" on the board and in --sim alike.
void Supervisor::pollPairingButton() {
  if (!pairingButton_) return;
  const rt::RuntimeSnapshot s = handoffs_.latest();
  if (s.tick == 0) return;
  button_.poll(pairingButton_, s.telemetry.now, services_.server(), services_.api());
}

void Supervisor::feedWatchdog() {
  const std::uint64_t beat = loop_.heartbeat();
  if (beat == lastBeat_) return;
  lastBeat_ = beat;
  services_.lastHeartbeatWallMs() = unixMsNow();
  sd_notify(0, "WATCHDOG=1");  // only while the control thread ticks
}

// --test-fault throw (--sim only): proves a fault of this thread leaves the field off.
void Supervisor::throwTestFault() const {
  if (cli_.testFault != TestFault::Throw || !cli_.sim) return;
  const rt::RuntimeSnapshot s = handoffs_.latest();
  if (s.tick > 0 && toSec(s.telemetry.now - s.start) >= cli_.testFaultAtS)
    throw std::runtime_error("test fault: exception on the main thread");
}

bool Supervisor::everySecond() {
  const rt::RuntimeSnapshot s = handoffs_.latest();
  if (s.tick > 0) followBankClass(handoffs_, s.telemetry);
  const bool updateStop = s.tick > 0 && services_.updateWatch().poll(s.telemetry, s.tick, unixMsNow());
  services_.outputsFault() = s.health.outputWriteErrors > 0 && !s.telemetry.field_enable && s.health.stopping;
  // The one SoC every screen shows (docs/dashboard.md "State of charge"), "unknown" while it is.
  const double soc = socShown(s.telemetry).pct;
  const std::string socText = std::isfinite(soc) ? std::to_string(std::lround(soc)) + "%" : "unknown";
  sd_notifyf(0, "STATUS=%s %s SoC %s duty %.1f%%%s", std::string(toString(s.telemetry.mode)).c_str(),
             std::string(toString(s.telemetry.stage)).c_str(), socText.c_str(), s.telemetry.duty_pct,
             services_.webDown() ? " (web server DOWN, see the journal)" : "");
  if (store_) store_->housekeeping(s, handoffs_.ledger.load(), s.tick > 100);
  if (s.health.adsEdgeFallback && !edgeFallbackLogged_) {
    edgeFallbackLogged_ = true;
    spdlog::error(
        "ADS1115 ALERT/RDY: no conversion-ready edges on GPIO line {}: single-shot pacing instead (CH1 "
        "~200 Hz). Wire ALERT/RDY to that line (10 kOhm pull-up) or set ads_alert_rdy_line = -1",
        settings_.hardware.ads_alert_rdy_line);
  }
  return updateStop;
}

void Supervisor::everyMinute() {
  const rt::RuntimeSnapshot s = handoffs_.latest();
  logLoopStats(s.loop, s.health, statsCadence_.atInfo(s.loop, s.health));
}

}  // namespace xr::app
