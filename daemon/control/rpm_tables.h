#pragma once
// field-control.md "RPM Tables": 10 breakpoints, linear interpolation, the
// first entry at or below the first breakpoint, the last entry at or above the
// last one (no extrapolation either side).
#include "params/params.h"

namespace xr {

double interpolateRpmTable(const RpmTable& rpmPoints, const RpmTable& values, double rpm);

// HiLow == 0 selects the Low-charge-rate tables (loadCapTablesForMode(0));
// never a runtime halving of the Normal ones.
const RpmTable& activeCapCurrentTable(const Params& p);
const RpmTable& activeCapPowerTable(const Params& p);
const RpmTable& activeMinDutyTable(const Params& p);

// I_cap in amps. capLimitMode 0: rpmCapCurrentTable. capLimitMode 1:
// rpmCapPowerTable (kW) converted through the live IBV; with no usable IBV the
// cap is 0 A (safe: no current can be commanded without knowing the voltage).
double getCapCurrentForRPM(const Params& p, double rpm, double ibv);

// rpmMinDuty (%), applied inside governor_apply().
double getMinDutyForRPM(const Params& p, double rpm);

}  // namespace xr
