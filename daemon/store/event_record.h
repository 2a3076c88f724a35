#pragma once
// One row of the event log as the store keeps it (store.h, event_queue.h).
#include <cstdint>
#include <string>

namespace xr {

struct EventRecord {
  std::int64_t id = 0;   // assigned by the store
  std::int64_t tMs = 0;  // UTC ms
  std::string level;     // toString(EventLevel)
  std::string code;      // toString(EventCode)
  std::string reason;    // toString(Reason)
  std::string message;   // describe(e)
  double a = 0.0, b = 0.0;
};

}  // namespace xr
