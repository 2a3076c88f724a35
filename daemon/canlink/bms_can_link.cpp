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
    changed |= decoder_.feed(*f, now) == can::BmsFrameResult::Accepted;
  }
  if (changed && post_) post_(decoder_.limits());
  const std::uint64_t rejects = decoder_.rejected();
  if (rejects != reportedRejects_ && (lastReport_ < 0 || now - lastReport_ >= fromSec(kBadFrameReportS))) {
    if (report_) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "BMS CAN: %llu bad frame(s) ignored (last: 0x%03X, %s)",
                    static_cast<unsigned long long>(rejects - reportedRejects_), decoder_.lastRejectedId(),
                    std::string(decoder_.lastRejectWhy()).c_str());
      report_(buf);
    }
    reportedRejects_ = rejects;
    lastReport_ = now;
  }
}

}  // namespace xr::canlink
