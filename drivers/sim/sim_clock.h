#pragma once
// The simulation's Clock: virtual time owned by SimWorld. sleepUntil(t)
// advances the world (plant + chips) to t and, unless speed is "max" (0),
// paces virtual time against wall time: speed 1 = real time, 10 = 10x.
#include <chrono>

#include "drivers/hal/clock.h"
#include "drivers/sim/sim_world.h"

namespace xr::sim {

class SimClock final : public Clock {
 public:
  // speed <= 0 means max (no pacing).
  SimClock(SimWorld& world, double speed = 0.0) : world_(world), speed_(speed) {}
  TimeNs now() const noexcept override { return world_.now(); }
  // Inline: at speed max (the benchmark, --speed max) it is the world
  // advance alone; the wall-clock pacing is out of line.
  void sleepUntil(TimeNs t) noexcept override {
    world_.advanceTo(t);
    if (!(speed_ <= 0.0)) pace();  // NaN paces, as before
  }
  void setSpeed(double s) noexcept;
  double speed() const noexcept { return speed_; }

 private:
  void pace() noexcept;

  SimWorld& world_;
  double speed_;
  bool anchored_ = false;
  std::chrono::steady_clock::time_point wallStart_;
  TimeNs simStart_ = 0;
};

}  // namespace xr::sim
