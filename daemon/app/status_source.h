#pragma once
// Shared read-side state of the running daemon for the web API and the
// supervisor: the hand-offs, the file params, recent events, health.
#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "core/events.h"
#include "core/time.h"

namespace xr::app {

// The newest events, kept in memory for GET /api/events (the store keeps
// them all). Written by the event pump thread, read by web threads.
class RecentEvents {
 public:
  static constexpr std::size_t kKeep = 1000;
  struct Item {
    std::int64_t id;
    double wallTimeS;
    Event event;
    std::string text;
  };
  void add(const Event& e, double wallTimeS, std::string text) {
    std::lock_guard lock(m_);
    items_.push_back(Item{++lastId_, wallTimeS, e, std::move(text)});
    if (items_.size() > kKeep) items_.pop_front();
  }
  // Newest first, ids < before when given.
  std::vector<Item> query(std::size_t limit, std::int64_t before) const {
    std::lock_guard lock(m_);
    std::vector<Item> out;
    for (auto it = items_.rbegin(); it != items_.rend() && out.size() < limit; ++it) {
      if (before > 0 && it->id >= before) continue;
      out.push_back(*it);
    }
    return out;
  }

 private:
  mutable std::mutex m_;
  std::deque<Item> items_;
  std::int64_t lastId_ = 0;
};

}  // namespace xr::app
