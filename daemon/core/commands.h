#pragma once
// Operator commands: the same names in the HTTP API (POST /api/commands) and
// in scenario files (command = "..."). Applied by the regulator between ticks.
#include <cstdint>
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
  SetSoc,  // value = soc %
  SystemIdStart,
  TuningCommit,
  CvTuningCommit,
  WeatherMode,  // flag = active
  // "acknowledge_alarm": silences the buzzer for the alarm sounding now, not
  // the protection (docs/protections.md "Acknowledging an alarm").
  AcknowledgeAlarm,
};

struct Command {
  CommandType type = CommandType::Auto;
  double value = 0.0;  // duty % for Manual, SoC % for SetSoc
  bool flag = false;   // active for WeatherMode
  // Non-zero: the control thread posts whether the regulator applied or
  // refused it (runtime/handoffs.h CommandAcks), so the HTTP answer can say.
  std::uint32_t ackId = 0;
};

std::string_view toString(CommandType t);
std::optional<CommandType> parseCommandType(std::string_view name);
// Name of the numeric or boolean argument the command needs ("duty",
// "soc_pct", "active"), or empty when it takes none.
std::string_view commandArgument(CommandType t);
// Why the regulator refuses t when it does (Regulator::command returns false),
// for the API's error answer.
std::string_view refusalReason(CommandType t);

}  // namespace xr
