#pragma once
// Safe state on the fatal exit paths (docs/architecture.md): std::terminate and
// the fatal signals SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGSYS
// (runtime/signals.h) run a fixed list
// of async-signal-safe actions registered at start — pwrite() of prepared
// bytes on descriptors opened at start (sysfs duty_cycle "0", the simulation
// output mirror) and callbacks that only issue a syscall (a libgpiod line
// set LOW) — then write one prepared line naming the signal to stderr (the
// journal) and die with the original signal.
#include <sys/types.h>

#include <cstddef>

namespace xr::rt::fatal {

inline constexpr std::size_t kMaxActions = 8;
inline constexpr std::size_t kMaxBytes = 96;

// Register before the control thread starts (not thread-safe against a
// concurrent fatal signal). False when the table is full or bytes too long.
// The descriptor stays owned by the caller and must stay open.
bool addWrite(int fd, const void* bytes, std::size_t len, off_t offset);
// fn must be async-signal-safe (syscalls only, no allocation, no locks).
bool addCallback(void (*fn)(void*) noexcept, void* ctx);
// Remove every action (tests; a clean stop that closed the descriptors).
void clearActions();

// Run every action now. Async-signal-safe; used by the handlers and by the
// daemon's own last-resort paths (an exception escaping a thread).
void driveSafeNow() noexcept;

// Install the signal handlers (on an alternate stack, so a stack overflow
// still reaches them) and std::set_terminate. Idempotent.
void install();
// Give the calling thread an alternate signal stack (the control thread
// calls this too; the main thread gets one from install()).
void installAltStackForThisThread();

// True once a fatal signal or std::terminate began: the control cycle then
// writes only the safe state, so that a fault signal handled on another
// thread is not undone by the next tick.
bool dying() noexcept;

// How many times driveSafeNow() ran (tests).
int timesDriven() noexcept;

}  // namespace xr::rt::fatal
