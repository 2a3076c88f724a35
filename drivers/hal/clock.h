#pragma once
// One control loop, two clocks (docs/architecture.md "Threads"): monotonic real time on the board,
// virtual time in simulation. Same loop body on both.
#include "core/time.h"

namespace xr {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual TimeNs now() const noexcept = 0;
  // Sleep (or, in simulation, advance virtual time) until the absolute time t.
  virtual void sleepUntil(TimeNs t) noexcept = 0;
};

}  // namespace xr
