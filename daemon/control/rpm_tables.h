#pragma once
// docs/control.md "RPM tables": 10 breakpoints, linear interpolation, the
// first entry at or below the first breakpoint, the last entry at or above the
// last one (no extrapolation either side).
#include <algorithm>
#include <cmath>

#include "params/params.h"

namespace xr {

inline double interpolateRpmTable(const RpmTable& pts, const RpmTable& v, double rpm) {
  if (!std::isfinite(rpm) || rpm <= pts[0]) return v[0];
  for (std::size_t i = 1; i < RPM_TABLE_SIZE; ++i) {
    if (rpm <= pts[i]) {
      const double span = pts[i] - pts[i - 1];
      if (span <= 0.0) return v[i];  // malformed (non-ascending) table: no division by zero
      const double f = (rpm - pts[i - 1]) / span;
      return v[i - 1] + f * (v[i] - v[i - 1]);
    }
  }
  return v[RPM_TABLE_SIZE - 1];
}

inline const RpmTable& activeCapCurrentTable(const Params& p) {
  return p.HiLow ? p.rpmCapCurrentTable : p.rpmCapCurrentTableLo;
}
inline const RpmTable& activeCapPowerTable(const Params& p) {
  return p.HiLow ? p.rpmCapPowerTable : p.rpmCapPowerTableLo;
}
inline const RpmTable& activeMinDutyTable(const Params& p) {
  return p.HiLow ? p.rpmMinDutyTable : p.rpmMinDutyTableLo;
}

// I_cap in amps. capLimitMode 0: rpmCapCurrentTable. capLimitMode 1:
// rpmCapPowerTable (kW) converted through the live IBV; with no usable IBV the
// cap is 0 A (safe: no current can be commanded without knowing the voltage).
inline double getCapCurrentForRPM(const Params& p, double rpm, double ibv) {
  if (p.capLimitMode == 1) {
    if (!std::isfinite(ibv) || ibv < 1.0) return 0.0;
    return std::max(0.0,
                    interpolateRpmTable(p.rpmTableRPMPoints, activeCapPowerTable(p), rpm) * 1000.0 / ibv);
  }
  return std::max(0.0, interpolateRpmTable(p.rpmTableRPMPoints, activeCapCurrentTable(p), rpm));
}

// rpmMinDuty (%), applied inside governorApply().
inline double getMinDutyForRPM(const Params& p, double rpm) {
  return interpolateRpmTable(p.rpmTableRPMPoints, activeMinDutyTable(p), rpm);
}

}  // namespace xr
