#pragma once
// Deterministic noise: std::mt19937_64's output sequence is fixed by the
// standard, but std::normal_distribution is not (it differs between library
// versions), so the normal transform is our own (Marsaglia polar method, both values used).
#include <cmath>
#include <cstdint>
#include <random>

namespace xr::sim {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : gen_(seed) {}
  // Uniform in (0, 1]: 53 random bits, never 0 so log() is finite.
  double uniform() noexcept { return (double(gen_() >> 11) + 1.0) * 0x1.0p-53; }
  double normal() noexcept {
    if (hasSpare_) {
      hasSpare_ = false;
      return spare_;
    }
    // Marsaglia's polar method: no trigonometry, one log per two values;
    // both coordinates come from one 64-bit draw (32 bits each is plenty for
    // sensor noise).
    double u, v, s;
    do {
      const std::uint64_t r = gen_();
      u = (double(std::uint32_t(r)) + 0.5) * 0x1.0p-31 - 1.0;
      v = (double(std::uint32_t(r >> 32)) + 0.5) * 0x1.0p-31 - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0);
    const double m = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * m;
    hasSpare_ = true;
    return u * m;
  }
  double gauss(double sigma) noexcept { return sigma > 0.0 ? sigma * normal() : 0.0; }

 private:
  std::mt19937_64 gen_;
  double spare_ = 0.0;
  bool hasSpare_ = false;
};

}  // namespace xr::sim
