#include "control/pid.h"

#include <algorithm>
#include <cmath>

namespace xr {

Pid::Pid(double kp, double ki, double kd, Direction dir) : kp_(kp), ki_(ki), kd_(kd), direction_(dir) {}

void Pid::setMode(Mode mode) noexcept {
  if (mode == AUTOMATIC && mode_ == MANUAL) {
    // Bumpless initialisation (PID_v1 Initialize()).
    outputSum_ = clampOut(std::isfinite(output) ? output : outMin_);
    lastInput_ = std::isfinite(input) ? input : 0.0;
  }
  mode_ = mode;
}

void Pid::trackIntegratorTo(double target, double dtSec) noexcept {
  if (!(dtSec > 0.0) || !std::isfinite(target)) return;
  const double a = std::min(1.0, trackingGain_ * dtSec);
  outputSum_ = clampOut(outputSum_ + a * (target - outputSum_));
}

}  // namespace xr
