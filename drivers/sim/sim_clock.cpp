#include "drivers/sim/sim_clock.h"

#include <thread>

namespace xr::sim {

void SimClock::setSpeed(double s) noexcept {
  speed_ = s;
  anchored_ = false;  // re-anchor pacing at the next sleep
}

void SimClock::pace() noexcept {
  if (!anchored_) {
    anchored_ = true;
    wallStart_ = std::chrono::steady_clock::now();
    simStart_ = world_.now();
    return;
  }
  const double wallS = toSec(world_.now() - simStart_) / speed_;
  std::this_thread::sleep_until(wallStart_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                 std::chrono::duration<double>(wallS)));
}

}  // namespace xr::sim
