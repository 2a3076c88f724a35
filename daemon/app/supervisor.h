#pragma once
// The daemon's main thread while the control thread runs (docs/operations.md):
// signals, the systemd watchdog (fed only while the control loop ticks), the
// status line, the state database's housekeeping, the patch log, and the
// loop's figures in the journal (hourly while healthy, at debug each minute).
#include <chrono>
#include <cstdint>

#include "app/cli.h"
#include "app/control_thread.h"
#include "app/daemon_notices.h"
#include "app/daemon_services.h"
#include "app/pairing_button.h"
#include "app/presence_pairing.h"
#include "app/store_service.h"
#include "config/settings.h"
#include "runtime/control_loop.h"
#include "runtime/handoffs.h"

namespace xr::app {

class Supervisor {
 public:
  Supervisor(const CliOptions& cli, const Settings& settings, rt::ControlLoop& loop,
             const ControlThread& control, rt::Handoffs& handoffs, DaemonServices& services,
             StoreService* store, ButtonInput* pairingButton = nullptr)
      : cli_(cli),
        settings_(settings),
        loop_(loop),
        control_(control),
        handoffs_(handoffs),
        services_(services),
        store_(store),
        pairingButton_(pairingButton) {}

  // Until the loop finishes or the control thread fails: the exit code a
  // signal asked for (0 otherwise). Throws only on a fault of this thread.
  int run();

 private:
  void feedWatchdog();
  void pollPairingButton();
  void throwTestFault() const;
  bool everySecond();  // true: a pending update asks to stop now
  void everyMinute();

  const CliOptions& cli_;
  const Settings& settings_;
  rt::ControlLoop& loop_;
  const ControlThread& control_;
  rt::Handoffs& handoffs_;
  DaemonServices& services_;
  StoreService* store_;
  PresencePairing presence_;    // the ignition turned off-on-off-on opens pairing (docs/security.md)
  ButtonInput* pairingButton_;  // [pairing] button_line; null: none
  PairingButtonWatch button_;   // its press opens pairing too
  std::uint64_t lastBeat_ = 0;
  bool edgeFallbackLogged_ = false;
  LoopStatsCadence statsCadence_;
};

}  // namespace xr::app
