#pragma once
// "Not set up" as a state (docs/configuration.md "Not set up"). Until a
// battery type is named, in the file (`BatteryProfile`) or on the set-up
// page (which always sends it), nobody has said what the bank is, and the
// catalogue's values are a lead-acid guess. The regulator then charges only
// within limits that no common chemistry (LiFePO4, AGM, flooded, gel) is
// hurt by, and the headline says so.
#include <string>
#include <vector>

#include "config/battery_profiles.h"
#include "config/config.h"
#include "params/params.h"

namespace xr {

// The limits for a 12 V bank, scaled by the bank class of BulkVoltage.
// 14.0 V is at or below every published absorption voltage (LiFePO4 14.0-
// 14.6, gel 14.1-14.4, AGM 14.4-14.7, flooded 14.4-14.8; docs/sources.md P3.7)
// and 13.4 V at or below every float but flooded's upper end (LiFePO4 13.5
// or none, AGM 13.3-13.5, gel 13.5-13.8, flooded 13.2-13.5). A LiFePO4 cell
// must not be charged below 0 degC, nor any chemistry here above 45 degC
// without derating; 5 degC keeps a margin for the sensor's placement.
inline constexpr double kSetupPendingChargeV12 = 14.0;
inline constexpr double kSetupPendingFloatV12 = 13.4;
inline constexpr double kSetupPendingMinTempC = 5.0;
inline constexpr double kSetupPendingMaxTempC = 45.0;
// RebulkVoltage must stay under the lowered float: at or above it a full
// bank returns to bulk at once, and cycles bulk-absorption-float for ever.
// 0.2 V under 13.4 V is the catalogue's gap (12.9 under 13.5) scaled down.
inline constexpr double kSetupPendingRebulkGapV12 = 0.2;

// True when the file (with a scenario's [config]) or the dashboard names the
// battery type.
bool batteryChosen(const NameSet& fileNames, const NameSet& dashboardNames);

// p with the limits above applied: every voltage target (the stages', the
// TargetVoltageMode setpoint, ChargedVoltage, RebulkVoltage) lowered to them,
// the battery-temperature window narrowed to them, lead-acid temperature
// compensation off (it raises the voltage in the cold, which LiFePO4 must
// not see), and p.SetupCeilingV set so that the core clamps every target it
// computes (CV tuning's high phase included). `capped` gets the names whose
// value changed.
Params withSetupPendingLimits(const Params& p, NameSet& capped);

// The charge ceiling of p's bank while not set up (14.0 V at 12 V).
double setupPendingChargeCeiling(const Params& p);

// The values of a configured (not yet lowered) set that the limits above
// would have to lower although they do not lower with BulkVoltage: the
// setpoint of TargetVoltageMode, ChargedVoltage, RebulkVoltage. A file or a
// PATCH naming one is refused with these errors while not set up (docs/
// configuration.md "Not set up"); `key` is the parameter's name.
std::vector<ConfigError> checkSetupPendingTargets(const Params& configured);

// One line for the journal, --check-config and the dashboard: the limits in
// force for this bank, e.g. "at most 14.0 V, float 13.4 V, battery 5-45 degC".
std::string setupPendingLimitsText(const Params& p);

}  // namespace xr
