// What the supervisor does with a signal (see stop_signal.h).
#include "app/stop_signal.h"

#include <signal.h>
#include <spdlog/spdlog.h>
#include <systemd/sd-daemon.h>

#include "runtime/signals.h"

namespace xr::app {

void handleSignal(int sig, rt::ControlLoop& loop, bool& stopRequested, int& exitCode) {
  using rt::signals::Handling;
  const Handling h = rt::signals::handlingOf(sig);
  const char* name = rt::signals::name(sig);
  if (h == Handling::Ignore) {
    if (sig == SIGHUP)
      spdlog::info("SIGHUP ignored: parameters change through the API; restart to reload the file");
    else
      spdlog::warn("{} ignored: the regulator cannot be paused", name);
    return;
  }
  if (stopRequested) {
    spdlog::info("{}: already stopping", name);
    return;
  }
  if (h == Handling::Stop) {
    spdlog::info("{}: stopping through the controlled ramp", name);
  } else {
    exitCode = 128 + sig;
    spdlog::warn(
        "{}: not a signal xregulatord uses; stopping through the controlled ramp (field enable LOW), "
        "exit {} so that systemd restarts the regulator",
        name, exitCode);
  }
  sd_notify(0, "STOPPING=1\nSTATUS=stopping: ramping the field down");
  loop.requestStop();
  stopRequested = true;
}

}  // namespace xr::app
