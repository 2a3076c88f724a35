#pragma once
// A signal taken by the daemon's supervisor loop (runtime/signals.h says
// which are ignored and which stop): every signal that would end the process
// stops it through the controlled ramp, so the field is LOW before the
// process ends, and the journal says why.
#include "runtime/control_loop.h"

namespace xr::app {

// Sets stopRequested once the ramp is asked for; exitCode = 128 + sig for a
// signal xregulatord does not use (systemd restarts the regulator).
void handleSignal(int sig, rt::ControlLoop& loop, bool& stopRequested, int& exitCode);

}  // namespace xr::app
