#pragma once
// BmsCanLink: the BMS bus on the Asio side (never the RT thread). Drains a
// CanBus, decodes with the configured protocol, posts each change of the
// limits (the caller stores them in the control cycle's BmsLimits hand-off,
// like the slow sensors), logs every frame to an optional candump log, and
// reports bad frames at most once per kBadFrameReportS with their count.
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

#include "can/bms_codec.h"
#include "drivers/hal/can_bus.h"

namespace xr::canlink {

class BmsCanLink {
 public:
  using Post = std::function<void(const BmsLimits&)>;
  using Report = std::function<void(const std::string&)>;
  static constexpr double kBadFrameReportS = 30.0;

  BmsCanLink(CanBus& bus, can::BmsProtocol protocol, std::string interface, Post post, Report report);
  // Every frame sent and received goes to `log` (candump format; times in
  // seconds as given to poll()).
  void setLog(std::ostream* log) { log_ = log; }
  // Reads what is waiting (no blocking); `now` stamps the frames.
  void poll(TimeNs now);

  const can::BmsDecoder& decoder() const { return decoder_; }

 private:
  CanBus& bus_;
  can::BmsDecoder decoder_;
  std::string interface_;
  Post post_;
  Report report_;
  std::ostream* log_ = nullptr;
  TimeNs lastReport_ = -1;
  std::uint64_t reportedRejects_ = 0;
};

}  // namespace xr::canlink
