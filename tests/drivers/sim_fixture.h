#pragma once
// Shared bits for running the drivers against the simulator's chip models:
// a virtual time the SimI2cBus reads and a Clock over it.
#include "drivers/hal/clock.h"
#include "drivers/sim/sim_i2c_bus.h"

namespace xr::test {

struct VirtualTime {
  TimeNs now = 1'000'000'000;
};

class VirtualClock final : public Clock {
 public:
  explicit VirtualClock(VirtualTime& t) : t_(t) {}
  TimeNs now() const noexcept override { return t_.now; }
  void sleepUntil(TimeNs t) noexcept override {
    if (t > t_.now) t_.now = t;
  }
  // Simulated I2C/CPU latency: each now() call could advance time (tests of
  // late ADS edges set this).
 private:
  VirtualTime& t_;
};

}  // namespace xr::test
