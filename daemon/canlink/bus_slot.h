#pragma once
// BusSlot: one CAN bus the service needs, opened when it can be. On a board
// the interface may be missing (HAT not fitted, overlay not loaded, link
// down): the open fails, the slot reports it once per attempt and tries
// again after 1 s, 2 s, 4 s ... up to 60 s. The regulator never waits for
// it: a BMS bus that is down means no limits arrive and the control law's
// stale fallback (BmsFallbackCapA, REASON_BMS_STALE) holds meanwhile.
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "core/time.h"
#include "drivers/hal/can_bus.h"

namespace xr::canlink {

class BusSlot {
 public:
  // Opens the bus; throws (std::exception) when it cannot.
  using Open = std::function<std::unique_ptr<CanBus>()>;
  using Report = std::function<void(const std::string&)>;
  // For the dashboard events: `back` false = an open failed (the first of
  // an outage, then at most one per kFaultEventS), true = open again.
  using Fault = std::function<void(bool back, std::uint64_t failures, double retryS, TimeNs now)>;
  static constexpr double kFirstRetryS = 1.0, kMaxRetryS = 60.0, kFaultEventS = 30.0;

  BusSlot(std::string interface, Open open, Report report);
  // A bus that is always there (the simulator's segment): never reopened.
  BusSlot(std::string interface, CanBus& bus);

  // The bus, opening it first when an attempt is due; nullptr while down.
  CanBus* get(TimeNs now);
  // The bus stopped working (the caller saw it fail): close it and retry.
  void lost(TimeNs now, const std::string& why);
  // True once per successful (re)open: the caller starts its protocol over.
  bool takeOpened() {
    const bool o = opened_;
    opened_ = false;
    return o;
  }
  void onFault(Fault f) { fault_ = std::move(f); }
  const std::string& interface() const { return interface_; }
  bool up() const { return bus_ != nullptr; }
  std::uint64_t failures() const { return failures_; }

 private:
  void failed(TimeNs now, const std::string& why);
  std::string interface_;
  Open open_;
  Report report_;
  Fault fault_;
  TimeNs lastFaultEvent_ = -1;
  std::uint64_t outageFailures_ = 0;  // failed attempts since the bus was last up
  std::unique_ptr<CanBus> owned_;
  CanBus* bus_ = nullptr;
  TimeNs nextTry_ = 0;
  double retryS_ = kFirstRetryS;
  std::uint64_t failures_ = 0;
  bool opened_ = false;
};

}  // namespace xr::canlink
