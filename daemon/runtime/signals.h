#pragma once
// What xregulatord does with every signal (docs/security.md). No signal may
// end the process with the field enable left as it was:
//   Stop           SIGTERM, SIGINT: the controlled ramp, exit 0.
//   UnexpectedStop every other signal whose default action ends the process
//                  and that is not a fault (SIGQUIT, SIGUSR1/2, SIGALRM,
//                  SIGXCPU, SIGXFSZ, SIGPWR, SIGVTALRM, SIGPROF, SIGSTKFLT,
//                  SIGIO, the real-time signals): the same controlled ramp,
//                  then exit 128 + signal so systemd restarts the regulator.
//   Ignore         SIGHUP and the terminal stops (SIGTSTP, SIGTTIN, SIGTTOU):
//                  logged; a regulator cannot be paused with the field on.
//   Fatal          faults (SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL, SIGTRAP,
//                  SIGSYS): fatal_guard's handler drives the field LOW, writes
//                  one prepared line to stderr, and dies with the signal.
//   SigIgn         SIGPIPE: SIG_IGN (a vanished web client).
//   Harmless       default action is to ignore or continue (SIGCHLD, SIGCONT,
//                  SIGURG, SIGWINCH).
//   Uncatchable    SIGKILL, SIGSTOP: the unit's ExecStopPost
//                  xregulator-field-off and the hardware watchdog cover them.
// Stop, UnexpectedStop and Ignore are blocked in every thread (main blocks
// them before any thread exists) and taken synchronously by the supervisor
// with sigtimedwait(), so their handling may log and wait.
#include <signal.h>

namespace xr::rt::signals {

enum class Handling { Stop, UnexpectedStop, Ignore, Fatal, SigIgn, Harmless, Uncatchable };

Handling handlingOf(int sig);
// Every signal whose handling is Stop, UnexpectedStop or Ignore.
sigset_t waitedSet();
// Blocks waitedSet() in the calling thread and ignores SIGPIPE. Call first in
// main, before any thread exists.
void blockWaitedSignals();
// "SIGUSR1", "SIGRTMIN+3"; a static string, async-signal-safe.
const char* name(int sig);

}  // namespace xr::rt::signals
