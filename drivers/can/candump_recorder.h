#pragma once
// The candump log recorder (`--can-log FILE`): a CanBus that passes every
// call to the bus it wraps and writes each frame sent and received, in
// candump's log format (candump_log.h), to one shared stream. Several buses
// may share one CandumpSink; each line names its interface. Frames the
// inner bus refuses to send are not written (they never reached the wire).
// Single-threaded like the buses it wraps (the CAN service's thread, or the
// simulator's loop).
#include <functional>
#include <ostream>
#include <string>

#include "drivers/hal/can_bus.h"

namespace xr::can {

class CandumpSink {
 public:
  // `timeSec` stamps each line: seconds since the epoch on a board, since
  // the start of the run in simulation.
  CandumpSink(std::ostream& out, std::function<double()> timeSec) : out_(out), timeSec_(std::move(timeSec)) {}
  void write(const std::string& interface, const CanFrame& f);
  std::uint64_t lines() const { return lines_; }

 private:
  std::ostream& out_;
  std::function<double()> timeSec_;
  std::uint64_t lines_ = 0;
};

class RecordingCanBus final : public CanBus {
 public:
  RecordingCanBus(CanBus& inner, std::string interface, CandumpSink& sink)
      : inner_(inner), interface_(std::move(interface)), sink_(sink) {}
  bool send(const CanFrame& f) noexcept override;
  std::optional<CanFrame> receive(std::chrono::milliseconds timeout) noexcept override;
  CanBusStats stats() const noexcept override { return inner_.stats(); }

 private:
  CanBus& inner_;
  std::string interface_;
  CandumpSink& sink_;
};

}  // namespace xr::can
