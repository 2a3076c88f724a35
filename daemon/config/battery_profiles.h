#pragma once
// Battery profiles (docs/batteries.md): what a battery type sets.
//
// A profile is a table of published 12 V values at 25 degC (docs/sources.md
// §3.7-3.8, sources named beside each number in battery_profiles.cpp). A bank
// of N cells gets each voltage times N / cells-per-12-V, so one profile serves
// 12, 24 and 48 V. Currents are fractions of BatteryCapacity_Ah.
//
// applyBatteryProfile() is the one place the profile meets the file: every
// value the profile owns that the file (or the dashboard) did not set is
// reset to the catalogue default and then, unless the profile is "custom",
// set to the profile's value. Re-applying it with a different profile or
// more pinned names is therefore always correct.
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "params/params.h"

namespace xr {

// The order of BatteryProfile's choices in catalogue.def.
enum class BatteryProfileId { lifepo4 = 0, agm = 1, flooded = 2, gel = 3, custom = 4 };

// Published values of one chemistry, as a 12 V bank at 25 degC.
struct ProfileTable {
  BatteryProfileId id;
  int cellsPer12V;           // 4 LiFePO4, 6 lead-acid
  double bulkV12;            // BulkVoltage
  double absorptionV12;      // AbsorptionVoltage
  double floatV12;           // FloatVoltage
  double rebulkV12;          // RebulkVoltage
  bool useFloat;             // UseFloat (false: rests after absorption)
  double tailFractionC;      // TailCurrent_A = this x BatteryCapacity_Ah
  double absorptionHours;    // AbsorptionTimeoutMs
  double maxChargeRateC;     // MaximumAllowedBatteryAmps = this x BatteryCapacity_Ah
  double tempCompMvPerCell;  // TempCompMvPerCellC
  double tempCompMinC, tempCompMaxC;
  double chargeMinC, chargeFullCurrentC, chargeMaxC;
  bool tempRequired;          // BatteryTempRequired
  bool idleZeroCurrent;       // IdleZeroCurrent (rest at zero battery current after absorption)
  double rebulkDischargePct;  // RebulkDischarge_percent (0 = the current rule)
};

// The table of a profile; nullptr for custom.
const ProfileTable* profileTable(BatteryProfileId id);
std::string_view toString(BatteryProfileId id);

// Cells in series for a nominal system voltage (12/24/48).
int cellsForNominal(BatteryProfileId id, int nominalV);

// The catalogue names a profile may set (every profile owns the same set).
std::span<const std::string_view> profileOwnedNames();

using NameSet = std::set<std::string, std::less<>>;

struct ProfileApplied {
  Params params;
  NameSet setByProfile;  // owned names the profile filled (empty for custom)
};

// See the header comment. `pinned` are the names set by the file, a
// scenario's [config] or the dashboard; their values in p are kept.
ProfileApplied applyBatteryProfile(const Params& p, const NameSet& pinned);

// The values the file (or a scenario's [config]) pins that the chosen profile
// would set otherwise, each as "Name = file value (profile: its value)"; empty
// for custom. The packaged default file writes every key, so choosing a
// profile there changes nothing until those lines go: the start log and
// --check-config say so rather than leave the user believing the profile acts.
std::vector<std::string> profileValuesTheFileOverrides(const Params& effective, const NameSet& fileNames);
// The same as one line for the journal and --check-config; empty when none.
std::string profileShadowNotice(const Params& effective, const NameSet& fileNames);

// Names whose value in p differs from the catalogue default (a base set
// whose explicit names are not known, e.g. a test's Params).
NameSet namesDifferingFromDefaults(const Params& p);

// Checks a profile's own limits on the effective values (empty = fine):
// "AbsorptionVoltage 14.8 V is 3.7 V/cell, above the LiFePO4 limit 3.65 V/cell".
struct ProfileProblem {
  std::string name;     // the parameter named
  std::string message;  // value and limit
};
std::vector<ProfileProblem> checkProfileLimits(const Params& p);

}  // namespace xr
