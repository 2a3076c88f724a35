// The simulated outputs' change log: a ring of the newest changes.
#include "drivers/sim/sim_outputs.h"

#include <gtest/gtest.h>

namespace xr::sim {
namespace {

TEST(ChangeLog, KeepsTheNewestChangesOldestFirst) {
  ChangeLog log(4);
  EXPECT_TRUE(log.empty());
  for (int i = 1; i <= 3; ++i) log.record(i, i * 10.0);
  ASSERT_EQ(log.size(), 3u);
  EXPECT_EQ(log[0].t, 1);
  EXPECT_EQ(log.back().value, 30.0);
  for (int i = 4; i <= 10; ++i) log.record(i, i * 10.0);
  ASSERT_EQ(log.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(log[k].t, TimeNs(7 + k));
    EXPECT_EQ(log[k].value, double(7 + k) * 10.0);
  }
  EXPECT_EQ(log.back().t, 10);
  EXPECT_EQ(log.count(), 10u);
}

TEST(ChangeLog, ZeroCapacityOnlyCounts) {
  ChangeLog log(0);
  log.record(1, 1.0);
  log.record(2, 0.0);
  EXPECT_TRUE(log.empty());
  EXPECT_EQ(log.count(), 2u);
}

TEST(SimPwm, LogsOnlyChangesAtTheirTime) {
  TimeNs now = 5;
  SimPwm pwm(&now);
  EXPECT_TRUE(pwm.setDutyPercent(40));
  now = 7;
  EXPECT_TRUE(pwm.setDutyPercent(40));   // unchanged: not logged
  EXPECT_TRUE(pwm.setDutyPercent(150));  // clamped to 100
  ASSERT_EQ(pwm.dutyLog().size(), 2u);
  EXPECT_EQ(pwm.dutyLog()[0].t, 5);
  EXPECT_EQ(pwm.dutyLog().back().t, 7);
  EXPECT_EQ(pwm.dutyLog().back().value, 100.0);
}

}  // namespace
}  // namespace xr::sim
