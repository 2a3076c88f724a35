#pragma once
// Events on their way from the event pump's thread to the integrations'
// (docs/integrations.md "Alarms that reach the owner"): the pump's sink
// posts each event with its wall-clock stamp; the integrations thread takes
// them on its own timer and groups them into incidents. Bounded: events
// come a few per incident (the core rate-limits its own), so a full feed
// means the integrations thread is stuck; the newest are dropped and
// counted, never waited for. The control thread never touches it.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <utility>
#include <vector>

#include "core/events.h"

namespace xr::integrations {

class IncidentFeed {
 public:
  static constexpr std::size_t kCapacity = 512;

  // The event pump's thread.
  void post(const Event& e, double wallS) {
    std::lock_guard lock(m_);
    if (q_.size() >= kCapacity) {
      ++dropped_;
      return;
    }
    q_.emplace_back(e, wallS);
  }
  // The integrations' thread: everything queued, oldest first.
  std::vector<std::pair<Event, double>> take() {
    std::lock_guard lock(m_);
    std::vector<std::pair<Event, double>> out(q_.begin(), q_.end());
    q_.clear();
    return out;
  }
  std::uint64_t dropped() const {
    std::lock_guard lock(m_);
    return dropped_;
  }

 private:
  mutable std::mutex m_;
  std::deque<std::pair<Event, double>> q_;
  std::uint64_t dropped_ = 0;
};

}  // namespace xr::integrations
