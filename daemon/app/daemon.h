#pragma once
// The running xregulatord: wires the configuration, the store, the rig
// (simulated or real board), the control thread, the event pump, the CSV
// writer, the web server and the supervisor (sd_notify, statistics), and
// owns every exit path:
//   SIGTERM/SIGINT  → controlled ramp (SYS_MODE_OFF), then enable LOW and
//                     duty 0 — within 3 s — then exit 0
//   end of --duration / scenario (--speed max) → field off, exit 0
//   exception (any thread) → enable LOW, duty 0, exit 70
//   std::terminate, SIGSEGV/SIGABRT/SIGBUS/SIGFPE/SIGILL → async-signal-safe
//                     writes (fatal_guard) then death by the signal
#include "app/cli.h"
#include "config/settings.h"

namespace xr::app {

class Daemon {
 public:
  Daemon(Config config, CliOptions cli) : config_(std::move(config)), cli_(std::move(cli)) {}
  int run();

 private:
  Config config_;
  CliOptions cli_;
};

}  // namespace xr::app
