// roundEven(): the INA228 model's libm-free std::nearbyint.
#include "drivers/sim/fast_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "drivers/sim/prng.h"

namespace xr::sim {
namespace {

TEST(RoundEven, MatchesNearbyintIncludingTiesAndSpecials) {
  for (double x : {0.0, -0.0, 0.5, 1.5, 2.5, -0.5, -1.5, -2.5, 0.49999999999999994, 1e15 + 0.5, -1e15 - 0.5,
                   4503599627370495.5, 0x1.0p51, -0x1.0p51, 0x1.0p60, 1e300, -1e300}) {
    EXPECT_EQ(roundEven(x), std::nearbyint(x)) << x;
  }
  EXPECT_EQ(roundEven(std::numeric_limits<double>::infinity()), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(roundEven(std::numeric_limits<double>::quiet_NaN())));
  Rng r(3);
  for (int i = 0; i < 100000; ++i) {
    const double x = (r.uniform() - 0.5) * std::ldexp(1.0, int(r.next() % 40));
    ASSERT_EQ(roundEven(x), std::nearbyint(x)) << x;
    const double tie = std::floor(x) + 0.5;
    ASSERT_EQ(roundEven(tie), std::nearbyint(tie)) << tie;
  }
}

TEST(RoundEven, SameBitsAsTheMagicNumberForm) {
  // The x86-64 fast path must give exactly the doubles of the portable
  // form (which the simulator used before), zero signs included, or the
  // chip models' codes would move.
  auto bits = [](double d) {
    std::uint64_t b;
    std::memcpy(&b, &d, sizeof b);
    return b;
  };
  for (double x : {0.0, -0.0, 0.3, -0.3, 0.5, -0.5, -1.5, 2.5, -2.5, 0x1.0p51 - 0.5, -0x1.0p51 + 0.5,
                   0x1.0p51, 0x1.0p52 + 1.0, -0x1.0p62, 0x1.0p63, -0x1.0p63, 1e300, -1e300}) {
    EXPECT_EQ(bits(roundEven(x)), bits(roundEvenPortable(x))) << x;
  }
  EXPECT_EQ(roundEven(-std::numeric_limits<double>::infinity()), -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(roundEven(-std::numeric_limits<double>::quiet_NaN())));
  Rng r(11);
  for (int i = 0; i < 200000; ++i) {
    const double x = (r.uniform() - 0.5) * std::ldexp(1.0, int(r.next() % 60));
    ASSERT_EQ(bits(roundEven(x)), bits(roundEvenPortable(x))) << x;
    const double tie = std::floor(x) + 0.5;
    ASSERT_EQ(bits(roundEven(tie)), bits(roundEvenPortable(tie))) << tie;
  }
}

}  // namespace
}  // namespace xr::sim
