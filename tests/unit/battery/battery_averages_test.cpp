// BatteryAverages on its own (docs/batteries.md "Averages"): time-weighted,
// voltage only while measured, restore.
#include "battery/battery_averages.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xr {
namespace {

TEST(BatteryAverages, TheSocIsWeightedByTime) {
  BatteryAverages a;
  EXPECT_DOUBLE_EQ(a.avgSoc(), 0.0) << "no time yet";
  a.integrate(30.0, 12.8, true);
  a.commit(80.0);
  a.integrate(10.0, 12.0, true);
  a.commit(40.0);
  EXPECT_DOUBLE_EQ(a.avgSoc(), 70.0);
  EXPECT_DOUBLE_EQ(a.avgSocAllTime(), 70.0);
  EXPECT_DOUBLE_EQ(a.avgVoltageAllTime(), 12.6);
}

TEST(BatteryAverages, AnAbsentVoltageDoesNotPullTheMeanDown) {
  BatteryAverages a;
  a.integrate(10.0, 12.5, true);
  a.integrate(10.0, std::nan(""), false);
  a.commit(50.0);
  EXPECT_DOUBLE_EQ(a.avgVoltageAllTime(), 12.5);
}

TEST(BatteryAverages, RestoreCarriesTheLifetimeNotTheSession) {
  BatteryLedger l;
  l.socAccumulator_AllTime = 6000.0;
  l.totalSocSampleTime_AllTime = 100.0;
  l.voltageAccumulator_AllTime = -1.0;  // damaged: restarts at 0
  BatteryAverages a;
  a.restore(l);
  EXPECT_DOUBLE_EQ(a.avgSocAllTime(), 60.0);
  EXPECT_DOUBLE_EQ(a.avgSoc(), 0.0);
  BatteryLedger out;
  a.toLedger(out);
  EXPECT_DOUBLE_EQ(out.voltageAccumulator_AllTime, 0.0);
}

}  // namespace
}  // namespace xr
