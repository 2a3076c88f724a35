#pragma once
// One spelling of the finiteness test the core uses everywhere (the core is
// compiled as one translation unit, so file-local copies would collide).
#include <cmath>

namespace xr {

inline bool finite(double v) { return std::isfinite(v); }

}  // namespace xr
