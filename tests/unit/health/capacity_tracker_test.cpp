// CapacityTracker (docs/batteries.md "Measured capacity").
#include "battery/capacity_tracker.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xr {
namespace {

TEST(CapacityTracker, TwoSwingsOfThirtyPercentGiveAFigureOneDoesNot) {
  CapacityTracker c;
  EXPECT_EQ(c.knownSoc(100.0, true, 200.0), CapacityPointResult::Anchored);
  c.addAh(-64.0, 3600.0);  // 40 % of a 160 Ah bank out
  EXPECT_EQ(c.knownSoc(60.0, false, 200.0), CapacityPointResult::Measured);
  EXPECT_TRUE(std::isnan(c.measuredAh()));
  EXPECT_EQ(c.cycles(), 1);
  c.addAh(56.0, 3600.0);  // 35 % back in
  EXPECT_EQ(c.knownSoc(95.0, false, 200.0), CapacityPointResult::Measured);
  EXPECT_NEAR(c.measuredAh(), 160.0, 1e-9);
  EXPECT_EQ(c.cycles(), 2);
}

TEST(CapacityTracker, ASwingJustUnderThirtyPercentIsNotMeasured) {
  CapacityTracker c;
  c.knownSoc(100.0, true, 200.0);
  c.addAh(-47.9, 3600.0);
  EXPECT_EQ(c.knownSoc(70.1, false, 200.0), CapacityPointResult::Held);  // 29.9 %
  c.addAh(-0.2, 60.0);
  EXPECT_EQ(c.knownSoc(70.0, false, 200.0), CapacityPointResult::Measured);  // 30.0 %
  EXPECT_NEAR(c.lastSampleAh(), 48.1 / 0.30, 1e-9);
}

TEST(CapacityTracker, AFullChargeReplacesANearbyPointTheOthersDoNot) {
  CapacityTracker c;
  c.knownSoc(100.0, true, 200.0);
  c.addAh(5.0, 600.0);  // current into a full bank is not stored
  EXPECT_EQ(c.knownSoc(100.0, true, 200.0), CapacityPointResult::Anchored);
  EXPECT_DOUBLE_EQ(c.ledger().NetAh, 0.0);
  c.addAh(-10.0, 600.0);
  EXPECT_EQ(c.knownSoc(94.0, false, 200.0), CapacityPointResult::Held);
  EXPECT_DOUBLE_EQ(c.ledger().AnchorSocPct, 100.0);
  EXPECT_DOUBLE_EQ(c.ledger().NetAh, -10.0);
}

TEST(CapacityTracker, ImplausibleOrContraryCountsAreDropped) {
  CapacityTracker c;
  c.knownSoc(100.0, true, 200.0);
  c.addAh(+20.0, 3600.0);  // the count went up while the SoC fell: a wiring fault
  EXPECT_EQ(c.knownSoc(60.0, false, 200.0), CapacityPointResult::Rejected);
  c.addAh(-10.0, 3600.0);  // 10 Ah for 40 %: 25 Ah, under 0.3 x 200
  EXPECT_EQ(c.knownSoc(20.0, false, 200.0), CapacityPointResult::Rejected);
  EXPECT_EQ(c.cycles(), 0);
}

TEST(CapacityTracker, AnOldPointIsNotJoinedToANewOne) {
  CapacityTracker c;
  c.knownSoc(100.0, true, 200.0);
  c.addAh(-80.0, capacity_k::kMaxAnchorAge_s + 1.0);
  EXPECT_EQ(c.knownSoc(60.0, false, 200.0), CapacityPointResult::Anchored);
  EXPECT_EQ(c.cycles(), 0);
}

TEST(CapacityTracker, NewerSwingsWeighMoreSoAnAgeingBankIsFollowed) {
  CapacityTracker c;
  c.knownSoc(100.0, true, 200.0);
  for (int i = 0; i < 2; ++i) {  // two swings at 200 Ah
    c.addAh(-80.0, 3600.0);
    c.knownSoc(60.0, false, 200.0);
    c.addAh(80.0, 3600.0);
    c.knownSoc(100.0, true, 200.0);
  }
  EXPECT_NEAR(c.measuredAh(), 200.0, 1e-9);
  for (int i = 0; i < 3; ++i) {  // then at 160 Ah
    c.addAh(-64.0, 3600.0);
    c.knownSoc(60.0, false, 200.0);
    c.addAh(64.0, 3600.0);
    c.knownSoc(100.0, true, 200.0);
  }
  EXPECT_LT(c.measuredAh(), 170.0);
  EXPECT_GT(c.measuredAh(), 160.0);
}

TEST(CapacityTracker, ADamagedLedgerStartsAfresh) {
  CapacityLedger l;
  l.SumAh = std::nan("");
  l.Cycles = 3;
  CapacityTracker c;
  c.restore(l);
  EXPECT_EQ(c.cycles(), 0);
  EXPECT_EQ(c.ledger().AnchorValid, 0.0);
}

}  // namespace
}  // namespace xr
