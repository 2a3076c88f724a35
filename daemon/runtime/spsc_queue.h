#pragma once
// Bounded single-producer / single-consumer queue (docs/architecture.md "Threads"):
// commands in to the RT thread, events and telemetry rows out of it.
// Wait-free on both sides, no allocation after construction. Exactly one
// thread may push and exactly one may pop; callers with several producers
// serialise them on their own (non-RT) side.
#include <array>
#include <atomic>
#include <cstddef>
#include <new>
#include <optional>

namespace xr::rt {

inline constexpr std::size_t kCacheLine = 64;

template <typename T, std::size_t Capacity>
class SpscQueue {
  static_assert(Capacity >= 2 && (Capacity & (Capacity - 1)) == 0, "Capacity must be a power of two");

 public:
  static constexpr std::size_t capacity() { return Capacity; }

  // Producer side. False when full (the item is not queued).
  bool push(const T& item) noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tailCache_ == Capacity) {
      tailCache_ = tail_.load(std::memory_order_acquire);
      if (head - tailCache_ == Capacity) return false;
    }
    slots_[head & (Capacity - 1)] = item;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer side. False when empty.
  bool pop(T& out) noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == headCache_) {
      headCache_ = head_.load(std::memory_order_acquire);
      if (tail == headCache_) return false;
    }
    out = slots_[tail & (Capacity - 1)];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // Approximate (exact when called from either endpoint with the other idle).
  std::size_t size() const noexcept {
    return head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire);
  }
  bool empty() const noexcept { return size() == 0; }

 private:
  alignas(kCacheLine) std::atomic<std::size_t> head_{0};  // written by the producer
  std::size_t tailCache_ = 0;                             // producer's view of tail_
  alignas(kCacheLine) std::atomic<std::size_t> tail_{0};  // written by the consumer
  std::size_t headCache_ = 0;                             // consumer's view of head_
  alignas(kCacheLine) std::array<T, Capacity> slots_{};
};

}  // namespace xr::rt
