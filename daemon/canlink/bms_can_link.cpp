// BmsCanLink (see bms_can_link.h).
#include "canlink/bms_can_link.h"

#include <chrono>
#include <cstdio>
#include <utility>

#include "drivers/can/candump_log.h"

namespace xr::canlink {

BmsCanLink::BmsCanLink(CanBus& bus, can::BmsProtocol protocol, std::string interface, Post post,
                       Report report)
    : bus_(bus),
      decoder_(protocol),
      interface_(std::move(interface)),
      post_(std::move(post)),
      report_(std::move(report)) {}

void BmsCanLink::poll(TimeNs now) {
  bool changed = false;
  while (auto f = bus_.receive(std::chrono::milliseconds(0))) {
    if (log_) *log_ << can::formatCandump(toSec(now), interface_, *f) << '\n';
    if (f->error) {
      ++errorFrames_;
      lastErrorClass_ = f->id;
      continue;
    }
    if (decoder_.feed(*f, now) == can::BmsFrameResult::Accepted) {
      changed = true;
      lastAccepted_ = now;
    }
  }
  if (changed && post_) post_(decoder_.limits());
  if (decoder_.rejected() != seenRejected_) {
    seenRejected_ = decoder_.rejected();
    if (lastBadAt_ >= 0 && now - lastBadAt_ >= fromSec(ReportGate::kQuietS)) toldReasons_ = 0;
    lastBadAt_ = now;
    const std::uint32_t bit = 1u << static_cast<unsigned>(decoder_.lastReject());
    if ((toldReasons_ & bit) == 0) {
      if (toldReasons_ != 0) badGate_.restart();  // another kind of bad frame: told at once
      toldReasons_ |= bit;
    }
  }
  if (const std::uint64_t n = badGate_.due(decoder_.rejected(), now)) {
    if (postEvent_) {
      postEvent_(makeEvent(now, EventLevel::Warning, EventCode::BmsBadFrames, Reason::NONE,
                           static_cast<double>(n), decoder_.lastRejectedId(),
                           static_cast<int>(decoder_.lastReject())));
    } else if (report_) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "BMS CAN: %llu bad frame(s) ignored (last: 0x%03X, %s)",
                    static_cast<unsigned long long>(n), decoder_.lastRejectedId(),
                    std::string(decoder_.lastRejectWhy()).c_str());
      report_(buf);
    }
  }
  if (const std::uint64_t n = errorGate_.due(errorFrames_, now)) {
    if (postEvent_) {
      postEvent_(makeEvent(now, EventLevel::Warning, EventCode::CanErrorFrames, Reason::NONE,
                           static_cast<double>(n), lastErrorClass_, 0));
    } else if (report_) {
      char buf[120];
      std::snprintf(buf, sizeof buf, "CAN %s: %llu error frame(s) (last error class 0x%X)",
                    interface_.c_str(), static_cast<unsigned long long>(n), lastErrorClass_);
      report_(buf);
    }
  }
}

}  // namespace xr::canlink
