#pragma once
// Time in the core is injected, never read from a clock: monotonic nanoseconds.
#include <cstdint>

namespace xr {

using TimeNs = std::int64_t;

constexpr TimeNs fromMs(std::int64_t ms) { return ms * 1000000; }
constexpr TimeNs fromUs(std::int64_t us) { return us * 1000; }
constexpr TimeNs fromSec(double s) { return static_cast<TimeNs>(s * 1e9); }
constexpr double toSec(TimeNs t) { return static_cast<double>(t) * 1e-9; }
constexpr double toMs(TimeNs t) { return static_cast<double>(t) * 1e-6; }

}  // namespace xr
