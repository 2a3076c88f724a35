// BusSlot (see bus_slot.h).
#include "canlink/bus_slot.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <utility>

namespace xr::canlink {

BusSlot::BusSlot(std::string interface, Open open, Report report)
    : interface_(std::move(interface)), open_(std::move(open)), report_(std::move(report)) {}

BusSlot::BusSlot(std::string interface, CanBus& bus) : interface_(std::move(interface)), bus_(&bus) {
  opened_ = true;
}

CanBus* BusSlot::get(TimeNs now) {
  if (bus_ || !open_ || now < nextTry_) return bus_;
  try {
    owned_ = open_();
    bus_ = owned_.get();
    opened_ = bus_ != nullptr;
    if (bus_ && outageFailures_ > 0) {
      if (report_)
        report_("CAN " + interface_ + ": open again after " + std::to_string(outageFailures_) +
                " failed attempt(s)");
      if (fault_) fault_(true, outageFailures_, 0.0, now);
      outageFailures_ = 0;
      lastFaultEvent_ = -1;
    }
    retryS_ = kFirstRetryS;
  } catch (const std::exception& e) {
    failed(now, e.what());
  }
  return bus_;
}

void BusSlot::lost(TimeNs now, const std::string& why) {
  if (!open_) return;  // a borrowed bus is not ours to reopen
  owned_.reset();
  bus_ = nullptr;
  failed(now, why);
}

void BusSlot::failed(TimeNs now, const std::string& why) {
  ++failures_;
  ++outageFailures_;
  if (report_) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "; retry in %.0f s", retryS_);
    report_("CAN " + interface_ + ": " + why + buf);
  }
  if (fault_ && (lastFaultEvent_ < 0 || now - lastFaultEvent_ >= fromSec(kFaultEventS))) {
    fault_(false, outageFailures_, retryS_, now);
    lastFaultEvent_ = now;
  }
  nextTry_ = now + fromSec(retryS_);
  retryS_ = std::min(retryS_ * 2.0, kMaxRetryS);
}

}  // namespace xr::canlink
