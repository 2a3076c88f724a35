#pragma once
// Operator commands: the same names in the HTTP API (POST /api/commands) and
// in scenario files (command = "..."). Applied by the regulator between ticks.
#include <optional>
#include <string_view>

namespace xr {

enum class CommandType {
  Auto,           // "auto"
  Manual,         // "manual", value = duty %
  Off,            // "off"
  LimpHome,       // "limp_home"
  LimpHomeOff,    // "limp_home_off"
  ReenableField,  // "reenable_field" (clears T2 latch)
  ResetAlarmLatch,
  ResetSocGain,
  ResetAltZero,
  SetSoc,         // value = soc %
  SystemIdStart,
  TuningCommit,
  CvTuningCommit,
  WeatherMode,    // flag = active
};

struct Command {
  CommandType type = CommandType::Auto;
  double value = 0.0;  // duty % for Manual, SoC % for SetSoc
  bool flag = false;   // active for WeatherMode
};

std::string_view toString(CommandType t);
std::optional<CommandType> parseCommandType(std::string_view name);
// Name of the numeric or boolean argument the command needs ("duty",
// "soc_pct", "active"), or empty when it takes none.
std::string_view commandArgument(CommandType t);

}  // namespace xr
