#include "runtime/event_pump.h"

namespace xr::rt {

EventPump::EventPump(EventRing& ring, std::chrono::milliseconds pollInterval)
    : ring_(ring), pollInterval_(pollInterval) {}

EventPump::~EventPump() { stop(); }

void EventPump::addSink(Sink sink) { sinks_.push_back(std::move(sink)); }

void EventPump::start() {
  if (thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stop_ = false;
  }
  thread_ = std::thread([this] { run(); });
}

void EventPump::stop() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
  drainOnce();
}

void EventPump::deliver(const Event& e) {
  for (auto& sink : sinks_) {
    // A failing sink (store full, socket gone) must not stop the others.
    try {
      sink(e);
    } catch (...) {
    }
  }
}

std::size_t EventPump::drainOnce() {
  std::lock_guard lock(drainMutex_);
  std::size_t n = 0;
  Event e;
  while (ring_.pop(e)) {
    deliver(e);
    ++n;
  }
  if (side_) {
    std::array<Event, SideEvents::kCapacity> taken;
    const std::size_t k = side_->take(taken);
    for (std::size_t i = 0; i < k; ++i) deliver(taken[i]);
    n += k;
  }
  delivered_.fetch_add(n, std::memory_order_relaxed);
  return n;
}

void EventPump::run() {
  // The RT side never signals (it must not touch a mutex), so poll.
  std::unique_lock lock(mutex_);
  while (!stop_) {
    lock.unlock();
    drainOnce();
    lock.lock();
    cv_.wait_for(lock, pollInterval_, [this] { return stop_; });
  }
}

}  // namespace xr::rt
