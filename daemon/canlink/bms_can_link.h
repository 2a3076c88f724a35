#pragma once
// BmsCanLink: the BMS bus on the Asio side (never the RT thread). Drains a
// CanBus, decodes with the configured protocol, posts each change of the
// limits (the caller stores them in the control cycle's BmsLimits hand-off,
// like the slow sensors), logs every frame to an optional candump log, and
// reports bad frames and error frames at most once per ReportGate::kPeriodS
// with their count: as events (BmsBadFrames, CanErrorFrames) when it has
// somewhere to post them, else as journal lines.
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <utility>

#include "can/bms_codec.h"
#include "canlink/report_gate.h"
#include "core/events.h"
#include "drivers/hal/can_bus.h"

namespace xr::canlink {

class BmsCanLink {
 public:
  using Post = std::function<void(const BmsLimits&)>;
  using Report = std::function<void(const std::string&)>;
  using PostEvent = std::function<void(const Event&)>;
  static constexpr double kBadFrameReportS = ReportGate::kPeriodS;

  BmsCanLink(CanBus& bus, can::BmsProtocol protocol, std::string interface, Post post, Report report);
  // Every frame sent and received goes to `log` (candump format; times in
  // seconds as given to poll()).
  void setLog(std::ostream* log) { log_ = log; }
  // Reports go out as events from now on (the daemon: Handoffs::sideEvents).
  void setPostEvent(PostEvent post) { postEvent_ = std::move(post); }
  // Reads what is waiting (no blocking); `now` stamps the frames.
  void poll(TimeNs now);

  const can::BmsDecoder& decoder() const { return decoder_; }
  std::uint64_t errorFrames() const { return errorFrames_; }
  TimeNs lastAccepted() const { return lastAccepted_; }  // 0 = never

 private:
  CanBus& bus_;
  can::BmsDecoder decoder_;
  std::string interface_;
  Post post_;
  Report report_;
  PostEvent postEvent_;
  std::ostream* log_ = nullptr;
  ReportGate badGate_, errorGate_;
  std::uint64_t errorFrames_ = 0;
  TimeNs lastAccepted_ = 0;
  std::uint32_t lastErrorClass_ = 0;
  // The reasons for bad frames told in this incident (bit = BmsReject), and
  // when the last bad frame came: a new reason is told at once, once.
  std::uint32_t toldReasons_ = 0;
  std::uint64_t seenRejected_ = 0;
  TimeNs lastBadAt_ = -1;
};

}  // namespace xr::canlink
