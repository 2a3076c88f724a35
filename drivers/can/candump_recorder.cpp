// The candump log recorder (see candump_recorder.h).
#include "drivers/can/candump_recorder.h"

#include <exception>

#include "drivers/can/candump_log.h"

namespace xr::can {

void CandumpSink::write(const std::string& interface, const CanFrame& f) {
  out_ << formatCandump(timeSec_(), interface, f) << '\n';
  ++lines_;
}

bool RecordingCanBus::send(const CanFrame& f) noexcept {
  if (!inner_.send(f)) return false;
  try {
    sink_.write(interface_, f);
  } catch (const std::exception&) {
    // A log that cannot be written costs the log, never the bus.
  }
  return true;
}

std::optional<CanFrame> RecordingCanBus::receive(std::chrono::milliseconds timeout) noexcept {
  auto f = inner_.receive(timeout);
  if (f) {
    try {
      sink_.write(interface_, *f);
    } catch (const std::exception&) {
    }
  }
  return f;
}

}  // namespace xr::can
