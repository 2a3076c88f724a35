#pragma once
// The ONE place the non-parameter settings keys of xregulator.toml are named
// ([hardware], [hardware.frontend], [runtime], [web], [store], [log],
// [integrations.signalk|mqtt|victron]). The
// loader, the generated default file and docs/configuration.md all read this
// table, as the parameter catalogue does for parameters.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "config/settings.h"

namespace xr {

enum class SettingKind { String, Int, Float, Bool, IntList };

// Int (also hex addresses and line numbers), Float, Bool, String, IntList.
using SettingValue = std::variant<std::int64_t, double, bool, std::string, std::vector<std::int64_t>>;

struct SettingSpec {
  std::string_view table;  // "hardware", "hardware.frontend", "runtime", ...
  std::string_view key;    // "i2c_bus"
  SettingKind kind;
  std::string_view unit;
  double min;              // Int/Float/IntList elements: allowed range
  double max;
  std::string_view choices;  // String: comma-separated allowed values (empty = any)
  bool hex;                  // Int: written as 0x.. in the default file
  std::string_view help;
  SettingValue (*get)(const Settings&);
  void (*set)(Settings&, const SettingValue&);
};

std::span<const SettingSpec> settingsSchema();
const SettingSpec* findSetting(std::string_view table, std::string_view key);
// The distinct table names, in file order.
std::span<const std::string_view> settingsTables();

// Empty when v fits spec (type already matching kind), else the reason
// ("300000 is out of range: allowed 500 to 100000 us").
std::string checkSettingValue(const SettingSpec& spec, const SettingValue& v);

}  // namespace xr
