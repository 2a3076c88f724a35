#include "control/pid.h"

#include <algorithm>
#include <cmath>

namespace xr {

Pid::Pid(double kp, double ki, double kd, Direction dir) : kp_(kp), ki_(ki), kd_(kd), direction_(dir) {}

void Pid::SetMode(Mode mode) {
  if (mode == AUTOMATIC && mode_ == MANUAL) {
    // Bumpless initialisation (PID_v1 Initialize()).
    outputSum_ = clampOut(std::isfinite(output) ? output : outMin_);
    lastInput_ = std::isfinite(input) ? input : 0.0;
  }
  mode_ = mode;
}

bool Pid::Compute(double dtSec) {
  if (mode_ != AUTOMATIC || !(dtSec > 0.0) || !std::isfinite(input) || !std::isfinite(setpoint)) return false;
  const double sign = direction_ == DIRECT ? 1.0 : -1.0;
  const double error = setpoint - input;
  const double dInput = input - lastInput_;
  outputSum_ = clampOut(outputSum_ + sign * ki_ * error * dtSec);
  pTerm_ = sign * kp_ * error;
  dTerm_ = -sign * kd_ * dInput / dtSec;  // on measurement: no kick on setpoint steps
  output = clampOut(pTerm_ + outputSum_ + dTerm_);
  lastInput_ = input;
  return true;
}

void Pid::TrackIntegratorTo(double target, double dtSec) {
  if (!(dtSec > 0.0) || !std::isfinite(target)) return;
  const double a = std::min(1.0, trackingGain_ * dtSec);
  outputSum_ = clampOut(outputSum_ + a * (target - outputSum_));
}

}  // namespace xr
