#pragma once
// field-control.md "RPM Tables": 10 breakpoints, linear interpolation, the
// first entry at or below the first breakpoint, the last entry at or above the
// last one (no extrapolation either side).
// Inline: two lookups run on every AUTO tick (Regulator::step cost).
#include <algorithm>
#include <cmath>

#include "params/params.h"

namespace xr {

// Where `rpm` falls on the breakpoints: everything interpolateRpmTable()
// needs except the values, so two tables over the same breakpoints (min
// duty and cap, every AUTO tick) share one search. Same arithmetic, same bits.
struct RpmPosition {
  std::size_t i = 0;  // segment end (1..), or the entry to return as is
  double f = 0.0;     // fraction inside the segment
  bool exact = true;  // true: return values[i] (outside the table or a malformed span)
};

inline RpmPosition locateRpm(const RpmTable& pts, double rpm) {
  if (!std::isfinite(rpm) || rpm <= pts[0]) return {0, 0.0, true};
  for (std::size_t i = 1; i < RPM_TABLE_SIZE; ++i) {
    if (rpm <= pts[i]) {
      const double span = pts[i] - pts[i - 1];
      if (span <= 0.0) return {i, 0.0, true};  // malformed (non-ascending) table: no division by zero
      return {i, (rpm - pts[i - 1]) / span, false};
    }
  }
  return {RPM_TABLE_SIZE - 1, 0.0, true};
}

inline double rpmTableValue(const RpmTable& v, const RpmPosition& at) {
  return at.exact ? v[at.i] : v[at.i - 1] + at.f * (v[at.i] - v[at.i - 1]);
}

inline double interpolateRpmTable(const RpmTable& pts, const RpmTable& v, double rpm) {
  return rpmTableValue(v, locateRpm(pts, rpm));
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
// Split in two so the table part (a function of rpm and the Params only) can
// be kept while rpm does not change: capTableValueAt() is the kW or A entry,
// capCurrentFromTable() the conversion through this tick's IBV.
inline double capTableValueAt(const Params& p, const RpmPosition& at) {
  return rpmTableValue(p.capLimitMode == 1 ? activeCapPowerTable(p) : activeCapCurrentTable(p), at);
}
inline double capCurrentFromTable(const Params& p, double tableValue, double ibv) {
  if (p.capLimitMode == 1) {
    if (!std::isfinite(ibv) || ibv < 1.0) return 0.0;
    return std::max(0.0, tableValue * 1000.0 / ibv);
  }
  return std::max(0.0, tableValue);
}
inline double capCurrentAt(const Params& p, const RpmPosition& at, double ibv) {
  return capCurrentFromTable(p, capTableValueAt(p, at), ibv);
}
inline double getCapCurrentForRPM(const Params& p, double rpm, double ibv) {
  return capCurrentAt(p, locateRpm(p.rpmTableRPMPoints, rpm), ibv);
}

// rpmMinDuty (%), applied inside governor_apply().
inline double getMinDutyForRPM(const Params& p, double rpm) {
  return interpolateRpmTable(p.rpmTableRPMPoints, activeMinDutyTable(p), rpm);
}

}  // namespace xr
