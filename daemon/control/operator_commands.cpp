// OperatorCommands: the owner's field commands, each checked before it holds.
#include "control/operator_commands.h"

#include <cmath>

namespace xr {

std::optional<bool> OperatorCommands::apply(const Command& cmd) noexcept {
  switch (cmd.type) {
    case CommandType::Auto:
      manual_ = false;
      off_ = false;
      return true;
    case CommandType::Manual:
      // A duty outside 0..100 % (or none) is refused: the last command stands.
      if (!std::isfinite(cmd.value) || cmd.value < 0.0 || cmd.value > 100.0) return false;
      manual_ = true;
      manualDuty_ = cmd.value;
      off_ = false;
      return true;
    case CommandType::Off:
      off_ = true;
      return true;
    case CommandType::LimpHome:
      limpHome_ = true;
      return true;
    case CommandType::LimpHomeOff:
      limpHome_ = false;
      return true;
    case CommandType::WeatherMode:
      weatherMode_ = cmd.flag;
      return true;
    default:
      return std::nullopt;
  }
}

}  // namespace xr
