#pragma once
// Absolute-deadline control loop around ControlCycle (docs/architecture.md):
// deadlines start + k·period slept to with the Clock seam
// (clock_nanosleep(TIMER_ABSTIME) on the board, virtual time in simulation),
// period error measured on the wall clock, overruns detected and skipped.
// Stop: requestStop() (async-signal-safe) starts the controlled ramp; the
// loop ends when the field is off or the ramp budget is spent, then forces
// enable LOW + duty 0.
#include <atomic>
#include <cstdint>
#include <functional>

#include "drivers/hal/clock.h"
#include "runtime/control_cycle.h"
#include "runtime/loop_stats.h"

namespace xr::rt {

struct LoopConfig {
  TimeNs period = fromUs(2500);
  TimeNs duration = 0;                   // loop-clock time to run (0 = until stopped)
  TimeNs shutdownBudget = fromMs(2000);  // controlled ramp budget (then forced; total < 3 s)
  // Maps a loop deadline to the wall time it is due at; empty = do not
  // measure period error (--speed max has no deadlines).
  std::function<TimeNs(TimeNs)> wallDeadlineOf;
  const Clock* wall = nullptr;  // required when wallDeadlineOf is set
  // The control thread's own CPU time (threadCpuTime(): CLOCK_THREAD_CPUTIME_ID
  // on the daemon; a fake in tests). It tells whose an overrun is: a tick
  // that used a period of CPU is the daemon's; a tick that took a period of
  // wall time while using little CPU was preempted (a loaded machine, a
  // hypervisor stall). Empty: judged by the tick's wall length instead.
  std::function<TimeNs()> cpuTime;
};

enum class LoopExit { Stopped, DurationReached };

class ControlLoop {
 public:
  ControlLoop(ControlCycle& cycle, Clock& clock, LoopStats& stats, LoopConfig config);

  // Runs on the calling (control) thread until stopped or the duration is
  // reached. The field is safe (enable LOW, duty 0) when it returns.
  LoopExit run();

  void requestStop() noexcept { stop_.store(true, std::memory_order_relaxed); }
  // Fault path: end at the next iteration without the ramp (the caller has
  // already driven the safe state).
  void requestAbort() noexcept {
    abort_.store(true, std::memory_order_relaxed);
    stop_.store(true, std::memory_order_relaxed);
  }
  bool stopRequested() const noexcept { return stop_.load(std::memory_order_relaxed); }
  // Grows by one per tick: the supervisor's proof of life (sd_notify WATCHDOG=1).
  std::uint64_t heartbeat() const noexcept { return heartbeat_.load(std::memory_order_relaxed); }
  bool finished() const noexcept { return finished_.load(std::memory_order_acquire); }

 private:
  ControlCycle& cycle_;
  Clock& clock_;
  LoopStats& stats_;
  LoopConfig cfg_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> abort_{false};
  std::atomic<std::uint64_t> heartbeat_{0};
  std::atomic<bool> finished_{false};
};

}  // namespace xr::rt
