#include "drivers/sim/plant/alternator.h"

#include <algorithm>
#include <cmath>

namespace xr::sim {

AlternatorModel::AlternatorModel(const AlternatorConfig& c)
    : cfg_(c),
      tempF_(c.temp_f),
      invRated_(1.0 / std::max(1.0, c.rated_a)),
      invThermalTau_(1.0 / std::max(1e-3, c.thermal_tau_s)) {}

double AlternatorModel::rpmCurve(double rpm) const noexcept {
  if (rpm <= cfg_.cut_in_rpm) return 0.0;
  const double x = std::min(1.0, (rpm - cfg_.cut_in_rpm) / std::max(1.0, cfg_.full_rpm - cfg_.cut_in_rpm));
  // The typical concave output curve: most of the output by mid-range.
  const double curve = std::sqrt(x) * (1.0 + 0.05 * std::min(1.0, (rpm - cfg_.full_rpm) / cfg_.full_rpm));
  return std::max(0.0, curve);
}

double AlternatorModel::hotFactor() const noexcept {
  // Hot derating: a cold machine gives ~15 % more, rated at 200 degF, less above.
  if (tempF_ <= 77.0) return 1.15;
  if (tempF_ <= 200.0) return 1.15 - (0.15 / 123.0) * (tempF_ - 77.0);
  return std::max(0.6, 1.0 - 0.002 * (tempF_ - 200.0));
}

double AlternatorModel::availableFraction(double rpm) const noexcept { return rpmCurve(rpm) * hotFactor(); }

double AlternatorModel::coolingFactor(double rpm) const noexcept {
  // Fan cooling improves with speed; some convection when stopped.
  return 0.35 + 0.65 * std::min(1.5, rpm / std::max(1.0, cfg_.cruise_rpm));
}

void AlternatorModel::step(double fieldCmd, double rpm, double ambientF, double dt) noexcept {
  const double target = open_ ? 0.0 : std::clamp(fieldCmd, 0.0, 1.0);
  if (dt != lagDt_) {
    lagDt_ = dt;
    lagK_ = 1.0 - std::exp(-dt / std::max(1e-4, cfg_.field_tau_s));
  }
  field_ += (target - field_) * lagK_;
  if (rpm != curveRpm_) {
    curveRpm_ = rpm;
    curve_ = rpmCurve(rpm);
    coolRel_ = coolingFactor(rpm) / coolingFactor(cfg_.cruise_rpm);
  }
  amps_ = cfg_.rated_a * (curve_ * hotFactor()) * field_;
  // Thermal: C dT/dt = P - G(rpm) (T - Ta), normalised so that at cruise
  // RPM, rated output: Tss - Ta = thermal_rise_f and tau = thermal_tau_s.
  const double g = coolRel_;
  const double iRel = amps_ * invRated_;
  const double heat = cfg_.thermal_rise_f * (0.9 * iRel * iRel + 0.1 * field_);
  const double dT = (heat - g * (tempF_ - ambientF)) * invThermalTau_;
  tempF_ += dT * dt;
}

}  // namespace xr::sim
