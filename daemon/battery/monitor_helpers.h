#pragma once
// Small checks shared by the BatteryMonitor's source files and its parts
// (battery_*.cpp, soc_counter.cpp, shunt_gain.cpp, energy_counter.cpp).
#include <algorithm>
#include <cstdint>

#include "core/events.h"
#include "core/finite.h"
#include "core/freshness.h"
#include "core/inputs.h"

namespace xr::battery_detail {

// A reading usable at `now`: the core's one rule (core/freshness.h).
inline bool usable(const Reading& r, TimeNs now, std::int64_t maxAgeMs) {
  return fresh::withinMs(r, now, maxAgeMs);
}

inline double clampFinite(double v, double lo, double hi, double fallback) {
  if (!finite(v)) return fallback;
  return std::clamp(v, lo, hi);
}

// Battery events carry no protection reason.
inline Event makeEvent(TimeNs t, EventLevel level, EventCode code, double a = 0.0, double b = 0.0,
                       int detail = 0) {
  return xr::makeEvent(t, level, code, Reason::NONE, a, b, detail);
}

}  // namespace xr::battery_detail
