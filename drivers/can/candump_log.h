#pragma once
// candump's log format (`candump -l`, read by canplayer and canboatjs), one
// frame a line:   (1700000000.000000) can0 351#8C00F401F4010000
// 11-bit ids are written with 3 hex digits, 29-bit ids with 8; an error
// frame sets CAN_ERR_FLAG (0x20000000) in its 8-digit id, as the kernel does.
#include <optional>
#include <string>
#include <string_view>

#include "drivers/hal/can_bus.h"

namespace xr::can {

struct CandumpLine {
  double timeSec = 0.0;  // seconds since the epoch (or since start in simulation)
  std::string interface;
  CanFrame frame;
};

std::string formatCandump(double timeSec, std::string_view interface, const CanFrame& f);
// nullopt on a malformed line (the reader counts and skips it).
std::optional<CandumpLine> parseCandump(std::string_view line);

}  // namespace xr::can
