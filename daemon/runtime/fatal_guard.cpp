#include "runtime/fatal_guard.h"

#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <exception>

#include "runtime/signals.h"

namespace xr::rt::fatal {

namespace {

struct Action {
  int fd = -1;
  off_t offset = 0;
  std::size_t len = 0;
  char bytes[kMaxBytes] = {};
  void (*fn)(void*) noexcept = nullptr;
  void* ctx = nullptr;
};

// The one piece of global state of the runtime: a signal handler can reach
// nothing else. Filled before threads start, read-only afterwards.
std::array<Action, kMaxActions> gActions;
std::atomic<std::size_t> gCount{0};
std::atomic<int> gDriven{0};
std::atomic<bool> gInstalled{false};
std::atomic<bool> gDying{false};

// A fault signal may be sent from outside and run on any thread while the
// control thread keeps ticking: after the flag is up it writes only the safe
// state, and a write it had already begun is overwritten by the second
// drive after this pause (several control periods; nanosleep is
// async-signal-safe).
void driveSafeAndSettle() noexcept {
  gDying.store(true);
  driveSafeNow();
  timespec pause{0, 20'000'000};
  nanosleep(&pause, nullptr);
  driveSafeNow();
}

// signals.h: the faults. SIGTRAP and SIGSYS too: the kernel forces them on
// the faulting thread, so blocking them (like the other signals) would not
// keep them from killing the process.
constexpr int kFatalSignals[] = {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGSYS};

// Appends src to buf at *n (bounded); async-signal-safe.
void append(char* buf, std::size_t cap, std::size_t* n, const char* src) {
  while (*src && *n < cap) buf[(*n)++] = *src++;
}

// One line for the journal (stderr is the journal under systemd), written
// with one write(2) after the field is LOW.
void tellFatal(int sig) {
  char line[128];
  std::size_t n = 0;
  append(line, sizeof line - 1, &n, "xregulatord: fatal signal ");
  append(line, sizeof line - 1, &n, signals::name(sig));
  append(line, sizeof line - 1, &n, ": field enable LOW, duty 0\n");
  [[maybe_unused]] auto w = write(STDERR_FILENO, line, n);
}

void onFatalSignal(int sig) {
  driveSafeAndSettle();
  tellFatal(sig);
  // Die with the original signal (core dump, correct exit status): the
  // handler was installed with SA_RESETHAND, so this re-raise is default.
  signal(sig, SIG_DFL);
  raise(sig);
}

[[noreturn]] void onTerminate() {
  driveSafeAndSettle();
  static const char msg[] = "xregulatord: std::terminate: field enable LOW, duty 0\n";
  [[maybe_unused]] auto n = write(STDERR_FILENO, msg, sizeof(msg) - 1);
  std::abort();
}

}  // namespace

bool addWrite(int fd, const void* bytes, std::size_t len, off_t offset) {
  const std::size_t i = gCount.load();
  if (i >= kMaxActions || len > kMaxBytes || fd < 0) return false;
  Action& a = gActions[i];
  a = Action{};
  a.fd = fd;
  a.offset = offset;
  a.len = len;
  std::memcpy(a.bytes, bytes, len);
  gCount.store(i + 1);
  return true;
}

bool addCallback(void (*fn)(void*) noexcept, void* ctx) {
  const std::size_t i = gCount.load();
  if (i >= kMaxActions || fn == nullptr) return false;
  gActions[i] = Action{};
  gActions[i].fn = fn;
  gActions[i].ctx = ctx;
  gCount.store(i + 1);
  return true;
}

void clearActions() { gCount.store(0); }

void driveSafeNow() noexcept {
  gDriven.fetch_add(1, std::memory_order_relaxed);
  const std::size_t n = gCount.load();
  for (std::size_t i = 0; i < n; ++i) {
    const Action& a = gActions[i];
    if (a.fn) {
      a.fn(a.ctx);
    } else if (a.fd >= 0) {
      [[maybe_unused]] auto w = pwrite(a.fd, a.bytes, a.len, a.offset);
    }
  }
}

void installAltStackForThisThread() {
  // 64 KiB per thread, never freed (threads live for the process).
  constexpr std::size_t kSize = 64 * 1024;
  stack_t ss{};
  ss.ss_sp = std::malloc(kSize);
  if (!ss.ss_sp) return;
  ss.ss_size = kSize;
  ss.ss_flags = 0;
  sigaltstack(&ss, nullptr);
}

void install() {
  if (gInstalled.exchange(true)) return;
  installAltStackForThisThread();
  struct sigaction sa {};
  sa.sa_handler = onFatalSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_ONSTACK | SA_RESETHAND;
  for (int sig : kFatalSignals) sigaction(sig, &sa, nullptr);
  std::set_terminate(onTerminate);
}

int timesDriven() noexcept { return gDriven.load(); }

bool dying() noexcept { return gDying.load(std::memory_order_relaxed); }

}  // namespace xr::rt::fatal
