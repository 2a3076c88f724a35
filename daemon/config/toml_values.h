#pragma once
// toml++ node -> typed value conversions shared by the file loader and the
// flat scenario overrides. Internal to xr_config.
#include <string>
#include <variant>

#include <toml++/toml.h>

#include "config/param_values.h"
#include "config/settings_schema.h"

namespace xr::detail {

// "string \"abc\"", "integer 3", "table", ...: what the user wrote.
std::string describeNode(const toml::node& n);

// The value for spec, or why the node does not fit (wrong type or range),
// worded to include the value, the allowed range and the unit.
std::variant<ParamValue, std::string> paramValueFromNode(const ParamSpec& spec, const toml::node& n);
std::variant<SettingValue, std::string> settingValueFromNode(const SettingSpec& spec, const toml::node& n);

}  // namespace xr::detail
