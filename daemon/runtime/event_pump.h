#pragma once
// Events out of the RT thread: the control cycle copies each tick's
// EventBatch into an SPSC ring (never blocks, counts what it had to drop);
// the EventPump, a non-RT thread, drains the ring and hands every event to
// its sinks (journal via logEvent(), the store, the dashboard). Formatting
// (describe()) happens only there.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "core/events.h"
#include "runtime/side_events.h"
#include "runtime/spsc_queue.h"

namespace xr::rt {

class EventRing {
 public:
  static constexpr std::size_t kCapacity = 1024;
  // RT side: copy a batch in; events that do not fit are counted as dropped,
  // together with the ones the core itself dropped from its batch.
  void pushBatch(const EventBatch& batch) noexcept {
    for (std::size_t i = 0; i < batch.count; ++i) {
      if (!queue_.push(batch.items[i])) dropped_.fetch_add(1, std::memory_order_relaxed);
    }
    if (batch.dropped) dropped_.fetch_add(batch.dropped, std::memory_order_relaxed);
  }
  bool push(const Event& e) noexcept {
    if (queue_.push(e)) return true;
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  bool pop(Event& e) noexcept { return queue_.pop(e); }
  bool empty() const noexcept { return queue_.empty(); }
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }

 private:
  SpscQueue<Event, kCapacity> queue_;
  std::atomic<std::uint64_t> dropped_{0};
};

class EventPump {
 public:
  using Sink = std::function<void(const Event&)>;

  explicit EventPump(EventRing& ring, std::chrono::milliseconds pollInterval = std::chrono::milliseconds(20));
  ~EventPump();
  EventPump(const EventPump&) = delete;
  EventPump& operator=(const EventPump&) = delete;

  // Add sinks and sources before start().
  void addSink(Sink sink);
  // Events posted by non-RT threads (side_events.h), drained with the ring.
  void addSource(SideEvents& side) { side_ = &side; }
  void start();
  // Drains what is left, then joins.
  void stop();
  // Drain now on the calling thread (tests, and the final flush).
  std::size_t drainOnce();
  std::uint64_t delivered() const noexcept { return delivered_.load(std::memory_order_relaxed); }

 private:
  void run();
  void deliver(const Event& e);

  EventRing& ring_;
  SideEvents* side_ = nullptr;
  std::chrono::milliseconds pollInterval_;
  std::vector<Sink> sinks_;
  std::thread thread_;
  std::mutex mutex_;       // guards stop_
  std::mutex drainMutex_;  // one drain at a time (ring is single-consumer)
  std::condition_variable cv_;
  bool stop_ = false;
  std::atomic<std::uint64_t> delivered_{0};
};

}  // namespace xr::rt
