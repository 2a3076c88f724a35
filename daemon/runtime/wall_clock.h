#pragma once
// The one wall clock below the core (docs/architecture.md "One clock"): the
// time the store, the event list, the history and the day and charge
// summaries stamp their rows with. On the board it is the system clock. In
// simulation it is the wall time at start plus the simulated time since the
// loop started, so a 2 h charge at --speed 30 reads as 2 h and a 100 s fault
// as 100 s. Anything else below the core that needs the time of day (the
// integrations) takes it the same way, and their timeouts, refreshes and
// backoffs run on steadyNow(): simulated time in --sim, so a test of a
// one-minute forecast refresh at --speed 30 waits two seconds, not a minute.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>

#include "core/time.h"

namespace xr::rt {

class WallClock {
 public:
  static std::int64_t systemUnixMs() {
    return std::chrono::duration_cast<std::chrono::milliseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
  }

  // From now on: the wall time of this call plus loopElapsed() (the
  // simulated time since the loop started; read from the published
  // snapshot, so any thread may ask). Called once, before the threads that
  // read this clock start.
  // speed: simulated seconds per wall second (0 = as fast as it goes).
  void followSimulation(std::function<TimeNs()> loopElapsed, double speed = 1.0) {
    startUnixMs_ = systemUnixMs();
    steadyStart_ = std::chrono::steady_clock::now();
    speed_ = speed;
    loopElapsed_ = std::move(loopElapsed);
  }
  bool simulated() const { return static_cast<bool>(loopElapsed_); }

  // Monotonic time for timeouts, refreshes and backoffs: steady_clock on the
  // board; in simulation the steady time at start plus the simulated time.
  std::chrono::steady_clock::time_point steadyNow() const {
    if (!loopElapsed_) return std::chrono::steady_clock::now();
    return steadyStart_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::nanoseconds(loopElapsed_()));
  }

  // How long a real timer waits before steadyNow() is asked again when
  // `left` of this clock remains: on the board all of it, at most
  // kBoardRecheck (so a stop is seen within a second); in simulation `left`
  // at the simulation's speed, at most kSimulatedRecheck, so a loop slower
  // than its speed (a busy machine) is waited for, not overtaken.
  std::chrono::steady_clock::duration realWait(std::chrono::steady_clock::duration left) const {
    using std::chrono::steady_clock;
    if (!loopElapsed_)
      return std::clamp<steady_clock::duration>(left, steady_clock::duration::zero(), kBoardRecheck);
    const auto atSpeed = speed_ > 0.0 ? std::chrono::duration_cast<steady_clock::duration>(left / speed_)
                                      : kSimulatedRecheck / 10;
    return std::clamp<steady_clock::duration>(atSpeed, steady_clock::duration::zero(), kSimulatedRecheck);
  }

  std::int64_t unixMs() const {
    if (!loopElapsed_) return systemUnixMs();
    return startUnixMs_ + loopElapsed_() / 1'000'000;
  }

 private:
  static constexpr std::chrono::steady_clock::duration kSimulatedRecheck = std::chrono::milliseconds(200);
  static constexpr std::chrono::steady_clock::duration kBoardRecheck = std::chrono::seconds(1);
  std::int64_t startUnixMs_ = 0;
  std::chrono::steady_clock::time_point steadyStart_{};
  double speed_ = 1.0;
  std::function<TimeNs()> loopElapsed_;
};

}  // namespace xr::rt
