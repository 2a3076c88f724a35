#pragma once
// Rounding for the chip models' per-sample paths without a libm call:
// std::nearbyint is an out-of-line call on baseline x86-64 (roundsd needs
// SSE4.1), and the INA228 model rounds several values per raw sample.
#include <cmath>

namespace xr::sim {

// Round to the nearest integer, ties to even: exactly std::nearbyint in the
// default rounding mode. Adding 1.5 x 2^52 moves |x| < 2^51 into the binade
// where one ulp is 1, so the FPU's own round-to-nearest-even does the work;
// subtracting it back is exact. (Relies on IEEE doubles and no -ffast-math,
// which would fold the two operations away; the unit test checks it.)
inline double roundEven(double x) noexcept {
  constexpr double kMagic = 6755399441055744.0;              // 1.5 x 2^52
  if (!(std::fabs(x) < 0x1.0p51)) return std::nearbyint(x);  // huge (halves down to 2^52), inf, NaN: rare
  return (x + kMagic) - kMagic;
}

}  // namespace xr::sim
