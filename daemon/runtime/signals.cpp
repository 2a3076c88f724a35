#include "runtime/signals.h"

#include <array>
#include <cstdio>

namespace xr::rt::signals {

Handling handlingOf(int sig) {
  switch (sig) {
    case SIGTERM:
    case SIGINT:
      return Handling::Stop;
    case SIGHUP:
    case SIGTSTP:
    case SIGTTIN:
    case SIGTTOU:
      return Handling::Ignore;
    case SIGSEGV:
    case SIGABRT:
    case SIGBUS:
    case SIGFPE:
    case SIGILL:
    case SIGTRAP:
    case SIGSYS:
      return Handling::Fatal;
    case SIGPIPE:
      return Handling::SigIgn;
    case SIGCHLD:
    case SIGCONT:
    case SIGURG:
    case SIGWINCH:
      return Handling::Harmless;
    case SIGKILL:
    case SIGSTOP:
      return Handling::Uncatchable;
    default:
      // SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGXCPU, SIGXFSZ, SIGPWR,
      // SIGVTALRM, SIGPROF, SIGSTKFLT, SIGIO and SIGRTMIN..SIGRTMAX: all end
      // the process by default.
      return Handling::UnexpectedStop;
  }
}

sigset_t waitedSet() {
  sigset_t set;
  sigemptyset(&set);
  for (int sig = 1; sig <= SIGRTMAX; ++sig) {
    if (sig > SIGSYS && sig < SIGRTMIN) continue;  // reserved by the C library
    const Handling h = handlingOf(sig);
    if (h == Handling::Stop || h == Handling::UnexpectedStop || h == Handling::Ignore) sigaddset(&set, sig);
  }
  return set;
}

void blockWaitedSignals() {
  const sigset_t set = waitedSet();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  signal(SIGPIPE, SIG_IGN);
}

const char* name(int sig) {
  switch (sig) {
    case SIGHUP:
      return "SIGHUP";
    case SIGINT:
      return "SIGINT";
    case SIGQUIT:
      return "SIGQUIT";
    case SIGILL:
      return "SIGILL";
    case SIGTRAP:
      return "SIGTRAP";
    case SIGABRT:
      return "SIGABRT";
    case SIGBUS:
      return "SIGBUS";
    case SIGFPE:
      return "SIGFPE";
    case SIGKILL:
      return "SIGKILL";
    case SIGUSR1:
      return "SIGUSR1";
    case SIGSEGV:
      return "SIGSEGV";
    case SIGUSR2:
      return "SIGUSR2";
    case SIGPIPE:
      return "SIGPIPE";
    case SIGALRM:
      return "SIGALRM";
    case SIGTERM:
      return "SIGTERM";
    case SIGSTKFLT:
      return "SIGSTKFLT";
    case SIGCHLD:
      return "SIGCHLD";
    case SIGCONT:
      return "SIGCONT";
    case SIGSTOP:
      return "SIGSTOP";
    case SIGTSTP:
      return "SIGTSTP";
    case SIGTTIN:
      return "SIGTTIN";
    case SIGTTOU:
      return "SIGTTOU";
    case SIGURG:
      return "SIGURG";
    case SIGXCPU:
      return "SIGXCPU";
    case SIGXFSZ:
      return "SIGXFSZ";
    case SIGVTALRM:
      return "SIGVTALRM";
    case SIGPROF:
      return "SIGPROF";
    case SIGWINCH:
      return "SIGWINCH";
    case SIGIO:
      return "SIGIO";
    case SIGPWR:
      return "SIGPWR";
    case SIGSYS:
      return "SIGSYS";
    default:
      break;
  }
  // Real-time signals: names built once, on first use outside a handler
  // (the daemon only asks from the supervisor thread).
  static const auto rtNames = [] {
    std::array<std::array<char, 16>, 65> n{};
    for (int s = 0; s < 65; ++s) std::snprintf(n[static_cast<std::size_t>(s)].data(), 16, "SIGRTMIN+%d", s);
    std::snprintf(n[0].data(), 16, "SIGRTMIN");  // the names kill -l uses
    std::snprintf(n[static_cast<std::size_t>(SIGRTMAX - SIGRTMIN)].data(), 16, "SIGRTMAX");
    return n;
  }();
  if (sig >= SIGRTMIN && sig <= SIGRTMAX) return rtNames[static_cast<std::size_t>(sig - SIGRTMIN)].data();
  return "unknown signal";
}

}  // namespace xr::rt::signals
