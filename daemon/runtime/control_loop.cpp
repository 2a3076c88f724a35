#include "runtime/control_loop.h"

namespace xr::rt {

ControlLoop::ControlLoop(ControlCycle& cycle, Clock& clock, LoopStats& stats, LoopConfig config)
    : cycle_(cycle), clock_(clock), stats_(stats), cfg_(std::move(config)) {
  if (cfg_.period <= 0) cfg_.period = fromUs(2500);
}

LoopExit ControlLoop::run() {
  const TimeNs start = clock_.now();
  cycle_.setStart(start);
  TimeNs next = start;
  bool ramping = false;
  TimeNs rampStart = 0;
  LoopExit exit = LoopExit::Stopped;
  // Wall-clock deadlines (board, paced simulation); fixed for the run.
  const bool paced = cfg_.wallDeadlineOf && cfg_.wall;

  for (;;) {
    if (abort_.load(std::memory_order_relaxed)) break;
    if (!ramping && stopRequested()) {
      ramping = true;
      rampStart = clock_.now();
      cycle_.beginShutdown();
    }
    if (ramping && (cycle_.fieldIsOff() || clock_.now() - rampStart >= cfg_.shutdownBudget)) break;
    if (!ramping && cfg_.duration > 0 && next - start >= cfg_.duration) {
      exit = LoopExit::DurationReached;
      break;
    }

    cycle_.serviceEdges(next);  // ADS1115 ready edges until the deadline (if wired)
    clock_.sleepUntil(next);
    const TimeNs woke = paced ? cfg_.wall->now() : clock_.now();
    if (paced) stats_.onPeriodError(woke - cfg_.wallDeadlineOf(next));
    const bool cpuMeasured = static_cast<bool>(cfg_.cpuTime);
    const TimeNs cpuBefore = cpuMeasured ? cfg_.cpuTime() : 0;
    cycle_.tick(clock_.now());
    const TimeNs tickCpu = cpuMeasured ? cfg_.cpuTime() - cpuBefore : 0;
    if (cpuMeasured) stats_.onTickCpu(tickCpu);
    // Single writer (this thread): a plain load + store, not a locked
    // read-modify-write on every tick.
    heartbeat_.store(heartbeat_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);

    next += cfg_.period;
    // At least one whole deadline passed without a tick: an overrun. Judged
    // on the wall clock when there is one (in a paced simulation the virtual
    // clock does not move while the tick runs). Skip the missed deadlines
    // rather than bursting to catch up.
    // Whose overrun is it (docs/performance.md, the soak: "0 overruns attributable to the
    // daemon")? With a CPU clock: the daemon's when the tick itself used a
    // period of CPU time; a tick preempted inside (another process, a
    // hypervisor stall) or a late wake-up is the machine's. Without one:
    // the tick's wall length (which counts such stalls as ours).
    TimeNs missed = 0;
    TimeNs tickWall = 0, period = cfg_.period;
    if (paced) {
      const TimeNs due = cfg_.wallDeadlineOf(next);
      period = cfg_.wallDeadlineOf(next + cfg_.period) - due;
      const TimeNs wallNow = cfg_.wall->now();
      const TimeNs late = wallNow - due;
      if (period > 0 && late >= period) missed = late / period;
      tickWall = wallNow - woke;
    } else {
      const TimeNs now = clock_.now();
      if (now >= next + cfg_.period) missed = (now - next) / cfg_.period;
      tickWall = now - woke;
    }
    const bool own = (cpuMeasured ? tickCpu : tickWall) >= period;
    if (missed > 0) {
      stats_.onOverrun(static_cast<std::uint64_t>(missed), own);
      next += missed * cfg_.period;
    }
  }
  cycle_.driveSafeState();
  cycle_.publishLatest();
  finished_.store(true, std::memory_order_release);
  return exit;
}

}  // namespace xr::rt
