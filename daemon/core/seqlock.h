#pragma once
// Newest-wins hand-off with one writer and any number of readers, the one
// seqlock of the daemon: the RT thread publishes the latest telemetry
// (HTTP/WebSocket, the CSV writer, sd_notify and the statistics logger read
// it), and the slow sensor threads (DS18B20, VE.Direct) publish their newest
// sample for the RT thread. The writer never waits; a reader retries while a
// write is in progress.
//
// The payload is stored as atomic words so that concurrent access is well
// defined (no data race, clean under ThreadSanitizer). Words are stored with
// release and loaded with acquire (instead of standalone fences, which TSan
// does not model): a reader that sees any word of a newer write is then
// guaranteed to see the odd/changed sequence number on its re-check (Boehm,
// "Can seqlocks get along with programming language memory models?").
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace xr {

template <typename T>
class SeqLock {
  static_assert(std::is_trivially_copyable_v<T>, "SeqLock payload must be trivially copyable");
  static constexpr std::size_t kWords = (sizeof(T) + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);

 public:
  SeqLock() noexcept { store(T{}); }

  // Writer (one thread only).
  void store(const T& value) noexcept {
    // Word by word straight from `value` (no zeroed staging copy: the
    // snapshot is several KB); only the last word may be partial.
    const auto* src = reinterpret_cast<const unsigned char*>(&value);
    constexpr std::size_t kTail = sizeof(T) - (kWords - 1) * sizeof(std::uint64_t);
    const std::uint64_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);
    for (std::size_t i = 0; i + 1 < kWords; ++i) {
      std::uint64_t w;
      std::memcpy(&w, src + i * sizeof(std::uint64_t), sizeof w);
      data_[i].store(w, std::memory_order_release);
    }
    std::uint64_t last = 0;
    std::memcpy(&last, src + (kWords - 1) * sizeof(std::uint64_t), kTail);
    data_[kWords - 1].store(last, std::memory_order_release);
    seq_.store(s + 2, std::memory_order_release);
  }

  // Reader: a consistent copy of the newest value. Returns its version
  // (even, grows by 2 per store) so callers can tell whether it is new.
  std::uint64_t load(T& out) const noexcept {
    std::array<std::uint64_t, kWords> words{};
    for (;;) {
      const std::uint64_t s1 = seq_.load(std::memory_order_acquire);
      if (s1 & 1U) continue;  // write in progress
      for (std::size_t i = 0; i < kWords; ++i) words[i] = data_[i].load(std::memory_order_acquire);
      if (seq_.load(std::memory_order_relaxed) == s1) {
        std::memcpy(static_cast<void*>(&out), words.data(), sizeof(T));
        return s1;
      }
    }
  }

  T load() const noexcept {
    T out;
    load(out);
    return out;
  }

  std::uint64_t version() const noexcept { return seq_.load(std::memory_order_acquire); }

 private:
  alignas(64) std::atomic<std::uint64_t> seq_{0};
  std::array<std::atomic<std::uint64_t>, kWords> data_{};
};

}  // namespace xr
