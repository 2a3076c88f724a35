#pragma once
// slewLimit(): the specification's asymmetric rate limiter (docs/control.md
// "Slew Rates and Time Constants"). Moves `current` toward `target` by at most
// riseRate*dt upward and fallRate*dt downward. Rates are per second.
#include <algorithm>
#include <cmath>

namespace xr {

inline double slewLimit(double current, double target, double riseRate, double fallRate, double dtSec) {
  if (!std::isfinite(current)) return target;
  if (dtSec <= 0.0) return current;
  const double up = riseRate * dtSec;
  const double down = fallRate * dtSec;
  if (target > current) return std::min(target, current + up);
  return std::max(target, current - down);
}

inline double clampd(double v, double lo, double hi) { return std::max(lo, std::min(v, hi)); }

}  // namespace xr
