#pragma once
// A protection part's surroundings in a unit test: the event batch, the
// last-trip record and a clock, so a part is driven through its own
// update() without the supervisor.
#include <algorithm>
#include <vector>

#include "core/events.h"
#include "protection/protection_log.h"

namespace xr::test {

struct PartLog {
  EventBatch ev;
  LastTrip trip;
  TimeNs t = fromSec(100.0);  // arbitrary monotonic origin
  FieldControlMode mode = FieldControlMode::MODE_NORMAL_AUTO_PID;
  std::vector<Event> seen;

  // The writer for the tick at t (events collected by collect()).
  ProtectionLog at() { return {ev, t, mode, trip}; }
  void collect() {
    for (std::size_t i = 0; i < ev.count; ++i) seen.push_back(ev.items[i]);
    ev.clear();
  }
  std::size_t count(EventCode c) const {
    return static_cast<std::size_t>(
        std::count_if(seen.begin(), seen.end(), [&](const Event& e) { return e.code == c; }));
  }
  std::size_t count(EventCode c, Reason r) const {
    return static_cast<std::size_t>(std::count_if(
        seen.begin(), seen.end(), [&](const Event& e) { return e.code == c && e.reason == r; }));
  }
};

}  // namespace xr::test
