#pragma once
// Whole-value hand-off with one writer and one reader, three preallocated
// slots, no allocation and no waiting on either side. Used for the whole-
// Params swap: a non-RT thread writes a validated Params, the RT thread picks
// it up between ticks (docs/architecture.md "Threads": "Parameters are one Params value, swapped
// whole between ticks, never mutated mid-tick").
#include <array>
#include <atomic>
#include <cstdint>

namespace xr::rt {

template <typename T>
class TripleBuffer {
  static constexpr std::uint8_t kIndexMask = 0x3;
  static constexpr std::uint8_t kFresh = 0x4;

 public:
  TripleBuffer() = default;
  explicit TripleBuffer(const T& initial) { slots_.fill(initial); }

  // Writer (one thread at a time): publish a whole new value.
  void write(const T& value) noexcept {
    slots_[back_] = value;
    const std::uint8_t old =
        middle_.exchange(static_cast<std::uint8_t>(back_ | kFresh), std::memory_order_acq_rel);
    back_ = old & kIndexMask;
  }

  // Reader: if a new value was published since the last call, make it the
  // current one and return true.
  bool update() noexcept {
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
    const std::uint8_t old = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = old & kIndexMask;
    return true;
  }

  // Reader: the current value (valid until the next update()).
  const T& current() const noexcept { return slots_[front_]; }

 private:
  std::array<T, 3> slots_{};
  alignas(64) std::atomic<std::uint8_t> middle_{1};  // index of the middle slot + fresh flag
  alignas(64) std::uint8_t back_ = 0;                // writer-owned
  alignas(64) std::uint8_t front_ = 2;               // reader-owned
};

}  // namespace xr::rt
