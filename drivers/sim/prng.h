#pragma once
// Deterministic noise: std::mt19937_64's output sequence is fixed by the
// standard, but std::normal_distribution is not (it differs between library
// versions), so the normal transform is our own (Box-Muller, both values used).
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
    const double r = std::sqrt(-2.0 * std::log(uniform()));
    const double a = 6.283185307179586 * uniform();
    spare_ = r * std::sin(a);
    hasSpare_ = true;
    return r * std::cos(a);
  }
  double gauss(double sigma) noexcept { return sigma > 0.0 ? sigma * normal() : 0.0; }

 private:
  std::mt19937_64 gen_;
  double spare_ = 0.0;
  bool hasSpare_ = false;
};

}  // namespace xr::sim
