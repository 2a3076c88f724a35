#pragma once
// Deterministic sensor noise, cheap enough to draw every simulated step.
//
// Generator: xoshiro256** (Blackman & Vigna), state seeded through
// splitmix64, so any 64-bit seed (0 included) gives a well-mixed state. Its
// output sequence is fixed by the algorithm, not by a library version (the
// reason std::normal_distribution is not used: it differs between standard
// libraries). One draw is a handful of shifts and multiplies, against a
// table refill every 312 draws for std::mt19937_64.
//
// Normal deviates: the sum of four 16-bit uniforms taken from ONE 64-bit draw
// (Irwin-Hall, n = 4), centred and scaled to unit variance. No log, sqrt or
// rejection loop. The shape is close to Gaussian (P(|z| < 1) = 0.67 against
// 0.683, P(|z| < 2) = 0.957 against 0.954, excess kurtosis -0.3) and
// bounded at +-2*sqrt(3) = +-3.46 sigma: a simulated sensor never produces
// the 5-sigma outlier a Gaussian tail would give once in a few million
// samples. For sensor noise on a regulator loop that is what we want to
// model (plain measurement jitter; spikes are injected as faults instead).
#include <cstdint>

namespace xr::sim {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) noexcept {
    std::uint64_t x = seed;
    for (auto& s : s_) s = splitmix64(x);
  }

  std::uint64_t next() noexcept {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  // Uniform in (0, 1]: 53 random bits, never 0 so log() is finite.
  double uniform() noexcept { return (double(next() >> 11) + 1.0) * 0x1.0p-53; }
  // Approximately standard normal (see the header comment), in [-3.47, 3.47].
  double normal() noexcept {
    const std::uint64_t r = next();
    // Four 16-bit lanes summed: two at a time in 32-bit halves, then the halves.
    const std::uint64_t pairs = (r & 0x0000FFFF0000FFFFull) + ((r >> 16) & 0x0000FFFF0000FFFFull);
    const std::uint64_t sum = (pairs & 0xFFFFFFFFull) + (pairs >> 32);  // 0 .. 4 x 65535
    // Each lane is uniform on (k + 0.5) / 65536: mean 1/2, variance 1/12, so
    // the sum has mean 2 and variance 1/3.
    constexpr double kScale = 1.7320508075688772 / 65536.0;  // sqrt(3) / 2^16
    return (double(std::int64_t(sum)) - 131070.0) * kScale;
  }
  double gauss(double sigma) noexcept { return sigma > 0.0 ? sigma * normal() : 0.0; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) noexcept { return (x << k) | (x >> (64 - k)); }
  static std::uint64_t splitmix64(std::uint64_t& x) noexcept {
    std::uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  std::uint64_t s_[4];
};

}  // namespace xr::sim
