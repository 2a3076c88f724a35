#pragma once
// The board's clock: CLOCK_MONOTONIC, absolute-deadline sleeps with
// clock_nanosleep(TIMER_ABSTIME) so wake-up error never accumulates.
#include "drivers/hal/clock.h"

namespace xr::rt {

class MonotonicClock final : public Clock {
 public:
  TimeNs now() const noexcept override;
  void sleepUntil(TimeNs t) noexcept override;
};

// CPU time the calling thread has used (CLOCK_THREAD_CPUTIME_ID): the
// control loop's measure of its own work, blind to time it spent preempted.
TimeNs threadCpuTime() noexcept;

// Virtual time paced against wall time (`--speed X`): virtual time comes
// from `inner` (the simulator's clock, which advances the plant in
// sleepUntil); after the inner clock reaches t, wait until the wall clock
// reaches wallStart + (t - virtStart) / speed.
class PacedClock final : public Clock {
 public:
  PacedClock(Clock& inner, Clock& wall, double speed);
  TimeNs now() const noexcept override { return inner_.now(); }
  void sleepUntil(TimeNs t) noexcept override;
  // The wall time at which virtual time t is due.
  TimeNs wallDeadline(TimeNs t) const noexcept;

 private:
  Clock& inner_;
  Clock& wall_;
  double speed_;
  TimeNs virtStart_;
  TimeNs wallStart_;
  bool anchored_ = false;
};

}  // namespace xr::rt
