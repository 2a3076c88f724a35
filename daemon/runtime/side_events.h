#pragma once
// SideEvents: events from the daemon's non-RT threads (the xr-can thread's
// bad BMS frames and bus faults) on their way to the same sinks
// as the control thread's (journal, /api/events and the dashboard, the
// store). The EventRing is single-producer and that producer is the control
// thread, so they cannot go there. The control thread never touches this
// queue: producers post under a mutex, the EventPump drains it on its own
// thread. Bounded: a producer that floods it loses the newest events, and
// they are counted, never waited for. Producers rate-limit their own
// events; the bound only protects memory.
#include <array>
#include <cstddef>
#include <cstdint>
#include <mutex>

#include "core/events.h"

namespace xr::rt {

class SideEvents {
 public:
  static constexpr std::size_t kCapacity = 32;

  // Any non-RT thread. False (and counted) when full.
  bool post(const Event& e) {
    std::lock_guard lock(mutex_);
    if (count_ == kCapacity) {
      ++dropped_;
      return false;
    }
    items_[(head_ + count_) % kCapacity] = e;
    ++count_;
    return true;
  }
  // The consumer: moves what is queued (oldest first) into `out`, returns
  // how many; the sinks run after the lock is released.
  std::size_t take(std::array<Event, kCapacity>& out) {
    std::lock_guard lock(mutex_);
    const std::size_t n = count_;
    for (std::size_t i = 0; i < n; ++i) out[i] = items_[(head_ + i) % kCapacity];
    head_ = (head_ + n) % kCapacity;
    count_ = 0;
    return n;
  }
  std::uint64_t dropped() const {
    std::lock_guard lock(mutex_);
    return dropped_;
  }

 private:
  mutable std::mutex mutex_;
  std::array<Event, kCapacity> items_{};
  std::size_t head_ = 0, count_ = 0;
  std::uint64_t dropped_ = 0;
};

}  // namespace xr::rt
