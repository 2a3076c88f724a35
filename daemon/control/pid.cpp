#include "control/pid.h"

#include <algorithm>
#include <cmath>

namespace xr {

Pid::Pid(double kp, double ki, double kd, Direction dir) : kp_(kp), ki_(ki), kd_(kd), direction_(dir) {}

void Pid::SetTunings(double kp, double ki, double kd) {
  if (kp < 0 || ki < 0 || kd < 0) return;  // library contract: gains are magnitudes
  kp_ = kp;
  ki_ = ki;
  kd_ = kd;
}

void Pid::SetOutputLimits(double min, double max) {
  if (!(min < max)) return;
  outMin_ = min;
  outMax_ = max;
  output = clampOut(output);
  outputSum_ = clampOut(outputSum_);
}

double Pid::clampOut(double v) const { return std::clamp(v, outMin_, outMax_); }

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

void Pid::TrackAppliedOutput(double applied, double dtSec) {
  if (!(dtSec > 0.0) || !std::isfinite(applied)) return;
  // Back-calculation: pulls outputSum toward the value that, with the present
  // P and D terms, reproduces what the actuator actually applied. Zero effect
  // while the output is not clamped downstream (applied == output), so the
  // linear loop keeps exactly its Kp/Ki/Kd.
  const double a = std::min(1.0, trackingGain_ * dtSec);
  const double wanted = applied - pTerm_ - dTerm_;
  outputSum_ = clampOut(outputSum_ + a * (wanted - outputSum_));
}

void Pid::TrackIntegratorTo(double target, double dtSec) {
  if (!(dtSec > 0.0) || !std::isfinite(target)) return;
  const double a = std::min(1.0, trackingGain_ * dtSec);
  outputSum_ = clampOut(outputSum_ + a * (target - outputSum_));
}

void Pid::ResetIntegratorTo(double v) {
  if (!std::isfinite(v)) return;
  outputSum_ = clampOut(v);
  output = outputSum_;
  lastInput_ = std::isfinite(input) ? input : lastInput_;
}

}  // namespace xr
