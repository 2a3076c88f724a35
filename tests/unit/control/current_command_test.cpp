// CurrentCommand on its own (docs/control.md "Command path"): the warm-up
// ceiling binds until WarmupCeilingSec after the field turned on and not at
// it; the BMS's battery cap is carried to the alternator as load + cap; the
// zero-current hold and the fast-OV cap.
#include "control/current_command.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace xr {
namespace {

CommandInputs cruising(TimeNs now) {
  CommandInputs in;
  in.now = now;
  in.dtSec = 0.1;
  in.rpm = 3000.0;
  in.IBV = 13.2;
  in.pidSignal = 30.0;
  in.Bcur = 5.0;
  return in;
}

TEST(CurrentCommandPart, WarmupCeilingBindsUntilItsEndNotAfter) {
  Params p;
  p.WarmupCeilingAmps = 10.0;
  CurrentCommand c;
  const TimeNs on = fromSec(100.0);
  c.onFieldTurnOn(on);
  const TimeNs end = on + fromSec(p.WarmupCeilingSec);
  c.update(cruising(end - 1), p);
  ASSERT_GT(c.I_cap(), 10.0);  // the table asks for more than the ceiling
  EXPECT_TRUE(c.warmupActive());
  EXPECT_DOUBLE_EQ(c.I_cmd(), 10.0);
  c.update(cruising(end), p);
  EXPECT_FALSE(c.warmupActive());
  EXPECT_GT(c.I_cmd(), 10.0);
}

TEST(CurrentCommandPart, TheBatteryCapLeavesTheHouseLoadServed) {
  Params p;
  CurrentCommand c;
  CommandInputs in = cruising(fromSec(1.0));
  const double free = c.update(in, p);
  ASSERT_GT(free, 30.0);
  in.bmsBatteryCapA = 2.0;  // the alternator carries 25 A of house load (30 - 5)
  EXPECT_DOUBLE_EQ(c.update(in, p), 27.0);
  EXPECT_TRUE(c.bmsCapActive());
  in.bmsBatteryCapA = free - 25.0 + 0.5;  // just over what the command asks: not binding
  EXPECT_DOUBLE_EQ(c.update(in, p), free);
  EXPECT_FALSE(c.bmsCapActive());
}

TEST(CurrentCommandPart, ZeroHoldAndTheFastOvCap) {
  Params p;
  CurrentCommand c;
  CommandInputs in = cruising(fromSec(1.0));
  const double u = c.update(in, p);
  c.applyFastOvCap(12.0);
  EXPECT_DOUBLE_EQ(c.uTargetAmps(), std::min(u, 12.0));
  c.applyFastOvCap(1e300);
  EXPECT_DOUBLE_EQ(c.uTargetAmps(), u);
  in.zeroHold = true;
  EXPECT_DOUBLE_EQ(c.update(in, p), 0.0);
  EXPECT_DOUBLE_EQ(c.I_cmd(), u);  // the caps still hold for the PID's max-selector
}

}  // namespace
}  // namespace xr
