#pragma once
// Rounding for the chip models' per-sample paths without a libm call:
// std::nearbyint is an out-of-line call on baseline x86-64 (roundsd needs
// SSE4.1), and the INA228 model rounds several values per raw sample.
#include <cmath>
#include <cstdint>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace xr::sim {

// Round to the nearest integer, ties to even: std::nearbyint in the default
// rounding mode, except that a zero result is always +0.0. Portable form:
// adding 1.5 x 2^52 moves |x| < 2^51 into the binade where one ulp is 1, so
// the FPU's own round-to-nearest-even does the work; subtracting it back is
// exact. (Relies on IEEE doubles and no -ffast-math, which would fold the two
// operations away; the unit test checks it.)
inline double roundEvenPortable(double x) noexcept {
  constexpr double kMagic = 6755399441055744.0;              // 1.5 x 2^52
  if (!(std::fabs(x) < 0x1.0p51)) return std::nearbyint(x);  // huge (halves down to 2^52), inf, NaN: rare
  return (x + kMagic) - kMagic;
}

inline double roundEven(double x) noexcept {
#if defined(__SSE2__)
  // x86-64: cvtsd2si rounds by MXCSR (nearest, ties to even, as nearbyint)
  // and is exact for |x| < 2^63; NaN, infinities and anything larger give
  // the one "indefinite" value INT64_MIN, which goes to nearbyint. Same
  // doubles as the portable form, zeros included (+0.0), fewer instructions
  // than its range check and two additions.
  const long long i = _mm_cvtsd_si64(_mm_set_sd(x));
  if (i == INT64_MIN) [[unlikely]]
    return std::nearbyint(x);
  return double(i);
#else
  return roundEvenPortable(x);
#endif
}

}  // namespace xr::sim
