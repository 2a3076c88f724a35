#pragma once
// Small checks shared by the BatteryMonitor's source files
// (battery_monitor.cpp, battery_auto_zero.cpp, battery_soc.cpp).
#include <algorithm>
#include <cstdint>

#include "core/events.h"
#include "core/finite.h"
#include "core/inputs.h"
#include "params/params.h"

namespace xr::battery_detail {

// A reading usable at `now`: has a value and is no older than maxAgeMs.
inline bool usable(const Reading& r, TimeNs now, std::int64_t maxAgeMs) {
  return finite(r.value) && r.stamp != 0 && now - r.stamp <= fromMs(maxAgeMs);
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

// A lead-acid profile (agm, flooded, gel): its rested voltage tells the SoC.
bool isLeadAcid(const Params& p);
// SoC % of a rested 12 V (6-cell) lead-acid bank at ~25 degC (battery_ocv.cpp).
double socFromRestVoltage12(double volts12);

}  // namespace xr::battery_detail
