// The loop's figures in the journal (docs/operations.md): the first minute,
// then hourly while healthy (1,440 lines a day before), and at once in the
// minute a count that means trouble grew.
#include <gtest/gtest.h>

#include "app/daemon_notices.h"

namespace xr::app {
namespace {

TEST(LoopStatsCadence, HealthyIsTheFirstMinuteThenHourly) {
  LoopStatsCadence c;
  rt::LoopStatsSummary s;
  rt::RuntimeHealth h;
  int lines = 0;
  for (int minute = 0; minute < 24 * 60; ++minute) lines += c.atInfo(s, h) ? 1 : 0;
  EXPECT_EQ(lines, 24);  // minute 0, 60, 120, ...
  LoopStatsCadence ten;
  lines = 0;
  for (int minute = 0; minute < 10; ++minute) lines += ten.atInfo(s, h) ? 1 : 0;
  EXPECT_EQ(lines, 1);
}

TEST(LoopStatsCadence, ACountThatMeansTroubleIsToldInTheMinuteItGrew) {
  LoopStatsCadence c;
  rt::LoopStatsSummary s;
  rt::RuntimeHealth h;
  EXPECT_TRUE(c.atInfo(s, h));  // the first minute
  EXPECT_FALSE(c.atInfo(s, h));
  s.overrunsOwn = 1;
  EXPECT_TRUE(c.atInfo(s, h));
  EXPECT_FALSE(c.atInfo(s, h)) << "told once, not every minute after";
  h.sensorReadErrors = 3;
  EXPECT_TRUE(c.atInfo(s, h));
  h.outputWriteErrors = 1;
  EXPECT_TRUE(c.atInfo(s, h));
  h.eventsDropped = 5;
  EXPECT_TRUE(c.atInfo(s, h));
  s.overruns = 40;  // late wake-ups (the machine's, not ours) alone are no news
  EXPECT_FALSE(c.atInfo(s, h));
}

}  // namespace
}  // namespace xr::app
