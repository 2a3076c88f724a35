#pragma once
// Checks of [integrations.*] and [can] (docs/integrations.md) that the loader
// makes: a value an integration could not use is a configuration error with
// its key, not a surprise on the boat's network later.
#include <string>
#include <utility>
#include <vector>

#include "config/settings.h"

namespace xr {

// True when text is a non-empty run of letters and digits (Signal K <id>).
bool isAlphanumericId(const std::string& text);

// (dotted key, message) for every problem; empty when all are usable. `can`
// is there for the one rule across tables: one source of BMS limits.
std::vector<std::pair<std::string, std::string>> checkIntegrations(const IntegrationsSettings& s,
                                                                   const CanSettings& can = {});

// A key an older version wrote that now lives elsewhere: why, or nullptr.
const char* retiredSetting(const std::string& dottedKey);
std::vector<std::pair<std::string, std::string>> checkCan(const CanSettings& s);

}  // namespace xr
