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

}  // namespace xr::app
