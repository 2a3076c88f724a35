#include "runtime/monotonic_clock.h"

#include <time.h>

#include <cerrno>

namespace xr::rt {

TimeNs MonotonicClock::now() const noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<TimeNs>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

void MonotonicClock::sleepUntil(TimeNs t) noexcept {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(t / 1'000'000'000);
  ts.tv_nsec = static_cast<long>(t % 1'000'000'000);
  // Restart after signals: the deadline is absolute, so no drift.
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

TimeNs threadCpuTime() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<TimeNs>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

PacedClock::PacedClock(Clock& inner, Clock& wall, double speed)
    : inner_(inner),
      wall_(wall),
      speed_(speed > 0 ? speed : 1.0),
      virtStart_(inner.now()),
      wallStart_(wall.now()) {}

TimeNs PacedClock::wallDeadline(TimeNs t) const noexcept {
  return wallStart_ + static_cast<TimeNs>(static_cast<double>(t - virtStart_) / speed_);
}

void PacedClock::sleepUntil(TimeNs t) noexcept {
  if (!anchored_) {
    // Anchor at the loop's first deadline, not at construction: start-up
    // time must not show up as lateness (and a catch-up burst).
    anchored_ = true;
    virtStart_ = t;
    wallStart_ = wall_.now();
  }
  inner_.sleepUntil(t);
  wall_.sleepUntil(wallDeadline(t));
}

}  // namespace xr::rt
