#include "control/governor.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xr {
namespace {

const GovernorLimits kLim{2.0, 90.0, 50.0};

TEST(Governor, BypassIsInstantButStillRespectsRpmMinDutyFloor) {
  EXPECT_DOUBLE_EQ(governorApply(60.0, 0.0, GovMode::GOV_BYPASS_SLEW, 5.0, 0.0025, kLim), 5.0);
}

TEST(Governor, BypassRespectsMinDutyWhenAboveTachFloor) {
  EXPECT_DOUBLE_EQ(governorApply(60.0, 0.0, GovMode::GOV_BYPASS_SLEW, 1.0, 0.0025, kLim), 2.0);
}

TEST(Governor, BypassRespectsMaxDuty) {
  EXPECT_DOUBLE_EQ(governorApply(10.0, 100.0, GovMode::GOV_BYPASS_SLEW, 1.0, 0.0025, kLim), 90.0);
  EXPECT_DOUBLE_EQ(governorApply(10.0, 40.0, GovMode::GOV_BYPASS_SLEW, 1.0, 0.0025, kLim), 40.0);
}

TEST(Governor, NormalSlewIsSymmetricAtDutyRampRate) {
  EXPECT_NEAR(governorApply(10.0, 80.0, GovMode::GOV_NORMAL_SLEW, 1.0, 0.1, kLim), 15.0, 1e-12);
  EXPECT_NEAR(governorApply(50.0, 10.0, GovMode::GOV_NORMAL_SLEW, 1.0, 0.1, kLim), 45.0, 1e-12);
}

TEST(Governor, NormalSlewNeverBelowFloorEvenComingUpFromZero) {
  EXPECT_DOUBLE_EQ(governorApply(0.0, 30.0, GovMode::GOV_NORMAL_SLEW, 5.0, 0.0025, kLim), 5.0);
}

TEST(Governor, HoldKeepsLastAppliedWithinBounds) {
  EXPECT_DOUBLE_EQ(governorApply(33.0, 80.0, GovMode::GOV_HOLD, 1.0, 0.1, kLim), 33.0);
  EXPECT_DOUBLE_EQ(governorApply(95.0, 80.0, GovMode::GOV_HOLD, 1.0, 0.1, kLim), 90.0);
}

TEST(Governor, NanRequestGivesTheFloorNotGarbage) {
  EXPECT_DOUBLE_EQ(governorApply(20.0, std::nan(""), GovMode::GOV_BYPASS_SLEW, 3.0, 0.01, kLim), 3.0);
}

TEST(Governor, ShutdownSpecialCaseGoesBelowMinDutyToZero) {
  double d = 4.0;
  for (int i = 0; i < 500; ++i) d = governorApplyShutdown(d, 0.0, GovMode::GOV_NORMAL_SLEW, 1.0, 0.01, 90.0);
  EXPECT_DOUBLE_EQ(d, 0.0);
  EXPECT_NEAR(governorApplyShutdown(4.0, 0.0, GovMode::GOV_NORMAL_SLEW, 1.0, 1.0, 90.0), 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(governorApplyShutdown(40.0, 0.0, GovMode::GOV_BYPASS_SLEW, 1.0, 0.01, 90.0), 0.0);
}

}  // namespace
}  // namespace xr
