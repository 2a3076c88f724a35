#pragma once
// The one wall clock below the core (docs/architecture.md "One clock"): the
// time the store, the event list, the history and the day and charge
// summaries stamp their rows with. On the board it is the system clock. In
// simulation it is the wall time at start plus the simulated time since the
// loop started, so a 2 h charge at --speed 30 reads as 2 h and a 100 s fault
// as 100 s. Anything else below the core that needs the time of day (the
// integrations) takes it the same way.
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
  void followSimulation(std::function<TimeNs()> loopElapsed) {
    startUnixMs_ = systemUnixMs();
    loopElapsed_ = std::move(loopElapsed);
  }
  bool simulated() const { return static_cast<bool>(loopElapsed_); }

  std::int64_t unixMs() const {
    if (!loopElapsed_) return systemUnixMs();
    return startUnixMs_ + loopElapsed_() / 1'000'000;
  }

 private:
  std::int64_t startUnixMs_ = 0;
  std::function<TimeNs()> loopElapsed_;
};

}  // namespace xr::rt
