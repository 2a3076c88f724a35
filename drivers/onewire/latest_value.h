#pragma once
// LatestValue<T>: single-writer, many-reader hand-off of the newest value
// (a seqlock over relaxed atomic words, so it is data-race free under the C++
// memory model and ThreadSanitizer). The slow sensor threads (DS18B20,
// VE.Direct) publish; the RT control thread reads without blocking or
// allocating. T must be trivially copyable.
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace xr {

template <typename T>
class LatestValue {
  static_assert(std::is_trivially_copyable_v<T>);
  static constexpr std::size_t kWords = (sizeof(T) + 7) / 8;

 public:
  LatestValue() noexcept { publish(T{}); }

  // Writer thread only.
  void publish(const T& v) noexcept {
    std::uint64_t w[kWords] = {};
    std::memcpy(w, &v, sizeof(T));
    const auto s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);  // odd: write in progress
    // Release on every word (no fences: ThreadSanitizer does not model
    // them): a reader that sees any new word also sees the odd sequence.
    for (std::size_t i = 0; i < kWords; ++i) words_[i].store(w[i], std::memory_order_release);
    seq_.store(s + 2, std::memory_order_release);
  }

  // Any thread. Retries while a write is in progress (the writer never
  // blocks, so this ends quickly); gives up after `maxTries` and returns false.
  bool tryRead(T* out, int maxTries = 64) const noexcept {
    for (int t = 0; t < maxTries; ++t) {
      const auto s1 = seq_.load(std::memory_order_acquire);
      if (s1 & 1) continue;
      std::uint64_t w[kWords];
      for (std::size_t i = 0; i < kWords; ++i) w[i] = words_[i].load(std::memory_order_acquire);
      if (seq_.load(std::memory_order_relaxed) == s1) {
        std::memcpy(out, w, sizeof(T));
        return true;
      }
    }
    return false;
  }
  T read() const noexcept {
    T v{};
    tryRead(&v, 1 << 20);
    return v;
  }
  std::uint64_t version() const noexcept { return seq_.load(std::memory_order_acquire) / 2; }

 private:
  std::atomic<std::uint64_t> seq_{0};
  std::array<std::atomic<std::uint64_t>, kWords> words_{};
};

}  // namespace xr
