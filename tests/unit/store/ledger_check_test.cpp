// The health ledger checked on load (store/ledger_check.h): edited or damaged
// rows gave a measured capacity of 100,000,000,000 Ah or 0 Ah, offered to the
// owner in one tap. A capacity outside 0.3x-2x of the set one, a non-finite or
// zero sum, is dropped and said; a plausible one is kept as it is.
#include "store/ledger_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace xr {
namespace {

// A ledger whose sums give `ah` over two swings of 50 %.
BatteryLedger measured(double ah) {
  BatteryLedger l;
  l.capacity.SumSwing = 1.0;
  l.capacity.SumAh = ah;
  l.capacity.Cycles = 2.0;
  l.capacity.AnchorValid = 1.0;
  l.capacity.AnchorSocPct = 100.0;
  l.capacity.NetAh = -12.5;
  return l;
}

TEST(LedgerCheck, APlausibleCapacityIsKeptAsItIs) {
  for (double ah : {60.0, 150.0, 200.0, 400.0}) {  // 0.3x and 2x of 200 Ah are in
    BatteryLedger l = measured(ah);
    const BatteryLedger before = l;
    EXPECT_EQ(dropImplausibleCapacity(l, 200.0), "") << ah;
    EXPECT_EQ(l, before) << ah;
  }
  BatteryLedger fresh;  // nothing measured yet
  EXPECT_EQ(dropImplausibleCapacity(fresh, 200.0), "");
}

TEST(LedgerCheck, ACapacityOutsideTheBoundsIsDroppedButTheKnownPointKept) {
  for (double ah : {1e11, 50000.0, 400.5, 59.9}) {
    BatteryLedger l = measured(ah);
    const std::string why = dropImplausibleCapacity(l, 200.0);
    EXPECT_NE(why.find("outside 0.3x-2x of the 200 Ah set"), std::string::npos) << ah << ": " << why;
    EXPECT_EQ(l.capacity.SumAh, 0.0);
    EXPECT_EQ(l.capacity.SumSwing, 0.0);
    EXPECT_EQ(l.capacity.Cycles, 0.0);
    EXPECT_EQ(l.capacity.AnchorValid, 1.0);  // the SoC anchor is another measurement
    EXPECT_EQ(l.capacity.NetAh, -12.5);
  }
}

TEST(LedgerCheck, ZeroAndNonFiniteSumsAreDropped) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (auto [ah, swing] : {std::pair{0.0, 1.0}, std::pair{100.0, 0.0}, std::pair{nan, 1.0},
                           std::pair{inf, 1.0}, std::pair{100.0, nan}, std::pair{-50.0, 1.0}}) {
    BatteryLedger l = measured(ah);
    l.capacity.SumSwing = swing;
    EXPECT_NE(dropImplausibleCapacity(l, 200.0), "") << ah << " / " << swing;
    EXPECT_EQ(l.capacity.Cycles, 0.0);
    EXPECT_TRUE(std::isfinite(l.capacity.SumAh) && std::isfinite(l.capacity.SumSwing));
  }
  BatteryLedger l = measured(150.0);
  l.capacity.AnchorSocPct = nan;  // a damaged known point goes too
  l.capacity.SumAh = inf;
  EXPECT_NE(dropImplausibleCapacity(l, 200.0), "");
  EXPECT_EQ(l.capacity.AnchorValid, 0.0);
}

}  // namespace
}  // namespace xr
