#include "core/commands.h"

#include <array>
#include <utility>

namespace xr {
namespace {
struct CommandName {
  CommandType type;
  std::string_view name;
  std::string_view argument;
};
constexpr std::array kCommands{
    CommandName{CommandType::Auto, "auto", ""},
    CommandName{CommandType::Manual, "manual", "duty"},
    CommandName{CommandType::Off, "off", ""},
    CommandName{CommandType::LimpHome, "limp_home", ""},
    CommandName{CommandType::LimpHomeOff, "limp_home_off", ""},
    CommandName{CommandType::ReenableField, "reenable_field", ""},
    CommandName{CommandType::ResetAlarmLatch, "reset_alarm_latch", ""},
    CommandName{CommandType::ResetSocGain, "reset_soc_gain", ""},
    CommandName{CommandType::ResetAltZero, "reset_alt_zero", ""},
    CommandName{CommandType::SetSoc, "set_soc", "soc_pct"},
    CommandName{CommandType::SystemIdStart, "system_id_start", ""},
    CommandName{CommandType::TuningCommit, "tuning_commit", ""},
    CommandName{CommandType::CvTuningCommit, "cv_tuning_commit", ""},
    CommandName{CommandType::WeatherMode, "weather_mode", "active"},
    CommandName{CommandType::AcknowledgeAlarm, "acknowledge_alarm", ""},
};
}  // namespace

std::string_view toString(CommandType t) {
  for (const auto& c : kCommands)
    if (c.type == t) return c.name;
  return "?";
}

std::optional<CommandType> parseCommandType(std::string_view name) {
  for (const auto& c : kCommands)
    if (c.name == name) return c.type;
  return std::nullopt;
}

std::string_view commandArgument(CommandType t) {
  for (const auto& c : kCommands)
    if (c.type == t) return c.argument;
  return "";
}

std::string_view refusalReason(CommandType t) {
  // The conditions of Regulator::command(), in the operator's words.
  switch (t) {
    case CommandType::Manual:
      return "the duty must be a number from 0 to 100 %";
    case CommandType::SetSoc:
      return "the state of charge must be a number from 0 to 100 %";
    case CommandType::SystemIdStart:
      return "system identification starts only in automatic mode with the field on (and not while it runs)";
    case CommandType::TuningCommit:
      return "TuningMode is off, or the tuning has no result to commit yet";
    case CommandType::CvTuningCommit:
      return "CVTuningMode is off, or the CV tuning has no result to commit yet";
    default:
      return "the regulator does not allow it now";
  }
}

}  // namespace xr
