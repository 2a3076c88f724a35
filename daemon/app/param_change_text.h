#pragma once
// The words of a "settings changed" event (docs/dashboard.md): every value a
// PATCH changed, old -> new, and who asked. Pure; web_api.cpp records it.
#include <string>
#include <vector>

#include "params/params.h"

namespace xr::app {

// "Settings changed by device "Anna's phone": FloatVoltage 13.4 → 13.3;
// UseFloat on → off; rpmCapCurrentTable point 4 40 → 45; AbsorptionVoltage
// 14.4 → 14.2 (follows the battery profile)". Values that differ between
// before and after but were not named in the patch moved with the profile
// and say so. Empty when nothing differs.
std::string paramChangeText(const Params& before, const Params& after, const std::vector<std::string>& named,
                            const std::string& source);

// The set-up page's save (a PATCH naming BatteryProfile and MaxTableValue)
// as one line: "Set-up: LiFePO4 12 V 280 Ah, alternator 120 A, belt 100 A"
// (docs/dashboard.md). The per-value list stays out of the event list: the
// set-up's result card and GET /api/params show every value.
bool isSetupSave(const std::vector<std::string>& named);
std::string setupSummaryText(const Params& after);

}  // namespace xr::app
