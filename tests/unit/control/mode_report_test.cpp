// ModeReport on its own (docs/operations.md "Events"): one ModeChanged per
// change and none while the mode holds; the first tick before an engine-speed
// reading stays quiet; FieldOn / FieldOff on the edges only.
#include "control/mode_report.h"

#include <gtest/gtest.h>

namespace xr {
namespace {

ModeDecision decided(FieldControlMode m, Reason r = Reason::NONE) {
  ModeDecision d;
  d.mode = m;
  d.reason = r;
  return d;
}

TEST(ModeReportPart, OneEventPerChangeNoneWhileTheModeHolds) {
  ModeReport r;
  EventBatch ev;
  const ModeDecision autoMode = decided(FieldControlMode::MODE_NORMAL_AUTO_PID);
  EXPECT_TRUE(r.changes(autoMode));  // the first tick always
  r.noteMode(autoMode, false, 1, ev);
  ASSERT_EQ(ev.count, 1u);
  EXPECT_EQ(ev.items[0].code, EventCode::ModeChanged);
  EXPECT_FALSE(r.changes(autoMode));
  r.noteMode(autoMode, false, 2, ev);
  EXPECT_EQ(ev.count, 1u);
  const ModeDecision lockout = decided(FieldControlMode::MODE_LOCKOUT_RAMP, Reason::REASON_LOCKOUT);
  r.noteMode(lockout, false, 3, ev);
  ASSERT_EQ(ev.count, 2u);
  EXPECT_EQ(ev.items[1].level, EventLevel::Warning);
  EXPECT_EQ(ev.items[1].a, static_cast<double>(FieldControlMode::MODE_NORMAL_AUTO_PID));  // the mode left
  EXPECT_EQ(r.reason(), Reason::REASON_LOCKOUT);
}

TEST(ModeReportPart, TheFirstTickWithoutAnRpmReadingIsQuiet) {
  ModeReport r;
  EventBatch ev;
  const ModeDecision low = decided(FieldControlMode::MODE_DISABLED_RAMP, Reason::REASON_RPM_LOW);
  r.noteMode(low, true, 1, ev);
  EXPECT_EQ(ev.count, 0u);
  EXPECT_FALSE(r.firstTick());
  r.noteMode(decided(FieldControlMode::MODE_NORMAL_AUTO_PID), false, 2, ev);
  EXPECT_EQ(ev.count, 1u);
}

TEST(ModeReportPart, FieldEdgesOnly) {
  ModeReport r;
  EventBatch ev;
  const ModeDecision d = decided(FieldControlMode::MODE_NORMAL_AUTO_PID);
  EXPECT_FALSE(r.noteField(false, d, 1, ev));
  EXPECT_TRUE(r.noteField(true, d, 2, ev));
  EXPECT_FALSE(r.noteField(true, d, 3, ev));
  EXPECT_FALSE(r.noteField(false, d, 4, ev));
  ASSERT_EQ(ev.count, 2u);
  EXPECT_EQ(ev.items[0].code, EventCode::FieldOn);
  EXPECT_EQ(ev.items[1].code, EventCode::FieldOff);
}

}  // namespace
}  // namespace xr
