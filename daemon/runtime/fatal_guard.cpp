#include "runtime/fatal_guard.h"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <exception>

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

constexpr int kFatalSignals[] = {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL};

void onFatalSignal(int sig) {
  driveSafeNow();
  // Die with the original signal (core dump, correct exit status): the
  // handler was installed with SA_RESETHAND, so this re-raise is default.
  signal(sig, SIG_DFL);
  raise(sig);
}

[[noreturn]] void onTerminate() {
  driveSafeNow();
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

}  // namespace xr::rt::fatal
