#pragma once
// The event log's writes, gathered (docs/performance.md "Storage writes"):
// every commit costs the SD card a few pages of WAL and their checkpoint
// copy, so a fault storm committing each event alone wrote ~12 MB an hour.
//   batching     at most one commit a second (or as soon as maxPending wait):
//                the first event after a quiet second is written at once, the
//                rest of a burst within the second; a power cut loses at most
//                the events of the last second.
//   repeats      rows of one kind (level, code, reason) are kept one by one up
//                to repeatKept in repeatWindowMs; the rest of that window are
//                counted and written as one summary row when the window ends
//                (or the store closes). The live alarms (buzzer, Home
//                Assistant, push) come from the event pump, not from these
//                rows: only the stored log is thinned.
// Pure: no clock, no I/O; the store passes its time in.
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "store/event_record.h"

namespace xr {

struct EventQueueOptions {
  std::int64_t commitEveryMs = 1000;
  std::size_t maxPending = 64;
  std::int64_t repeatWindowMs = 10 * 60 * 1000;
  int repeatKept = 5;  // 0: no limit, every row kept
};

class EventQueue {
 public:
  explicit EventQueue(EventQueueOptions o = {}) : opt_(o) {}
  // A new event: queued for the next write, or counted as a repeat.
  void push(const EventRecord& e);
  // Whether rows wait and may be written at nowMs (a second after the last
  // write, or a full queue).
  bool due(std::int64_t nowMs) const;
  // The rows to write now, oldest first: the queued events and one summary
  // per kind whose window has ended by nowMs (every window when `all`).
  std::vector<EventRecord> take(std::int64_t nowMs, bool all);
  // The rows were written (or failed) at nowMs: the next commit a second on.
  void written(std::int64_t nowMs) { lastWriteMs_ = nowMs; }
  std::size_t pending() const { return pending_.size(); }

 private:
  using Key = std::tuple<std::string, std::string, std::string>;  // level, code, reason
  struct Window {
    std::int64_t startMs = 0;
    int kept = 0;
    int repeats = 0;  // counted, not yet written
    std::int64_t firstRepeatMs = 0;
    EventRecord last;  // the latest repeat
  };
  bool ended(const Window& w, std::int64_t nowMs) const {
    return nowMs >= w.startMs + opt_.repeatWindowMs || nowMs < w.startMs;
  }
  void summarise(Window& w);  // a summary row into pending_ when repeats were counted

  EventQueueOptions opt_;
  std::vector<EventRecord> pending_;
  std::map<Key, Window> windows_;
  std::int64_t lastWriteMs_ = INT64_MIN / 2;
};

}  // namespace xr
