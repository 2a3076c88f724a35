#include "drivers/sim/sim_outputs.h"

#include <algorithm>
#include <cmath>

namespace xr::sim {

bool SimPwm::setDutyPercent(double pct) noexcept {
  if (failing_) return false;
  if (!std::isfinite(pct)) return false;  // sysfs would reject it too
  const double d = std::clamp(pct, 0.0, 100.0);
  if (d != duty_) {
    duty_ = d;
    dutyLog_.record(*now_, d);
  }
  return true;
}

bool SimPwm::setEnabled(bool on) noexcept {
  if (failing_) return false;
  if (on != enabled_) {
    enabled_ = on;
    enableLog_.record(*now_, on ? 1.0 : 0.0);
  }
  return true;
}

bool SimDigitalOutput::set(bool high) noexcept {
  if (high != level_) {
    level_ = high;
    log_.record(*now_, high ? 1.0 : 0.0);
  }
  return true;
}

bool SimWatchdog::keepAlive() noexcept {
  if (kicks_ > 0) longestGap_ = std::max(longestGap_, *now_ - last_);
  last_ = *now_;
  ++kicks_;
  closed_ = false;
  return true;
}

void SimWatchdog::closeClean() noexcept { closed_ = true; }

}  // namespace xr::sim
