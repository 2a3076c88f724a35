// AltCurrentAutoZero on its own (docs/batteries.md "Auto-zero"): its
// triggers at their thresholds and just below, the sampling window, the
// implausible mean, the reset.
#include "battery/battery_auto_zero.h"

#include <gtest/gtest.h>

#include <cmath>

#include "params/constants.h"

namespace xr {
namespace {

constexpr TimeNs kT0 = fromSec(1000.0);

AutoZeroInput at(TimeNs now, double rpm = 1500.0, double tempF = 150.0) {
  AutoZeroInput in;
  in.now = now;
  in.enabled = true;
  in.rpm = rpm;
  in.tempF = tempF;
  return in;
}

TEST(AltCurrentAutoZero, StartsOnTheHourNotJustBefore) {
  AltCurrentAutoZero z;
  z.begin(kT0);
  EventBatch ev;
  EXPECT_FALSE(z.checkTriggers(at(kT0 + fromMs(k::AUTO_ZERO_INTERVAL) - fromMs(1)), ev));
  EXPECT_FALSE(z.active());
  EXPECT_TRUE(z.checkTriggers(at(kT0 + fromMs(k::AUTO_ZERO_INTERVAL)), ev));
  EXPECT_TRUE(z.active());
  ASSERT_EQ(ev.count, 1u);
  EXPECT_EQ(ev.items[0].code, EventCode::AutoZeroStarted);
}

TEST(AltCurrentAutoZero, NeedsTheEngineTurningAndTheFeatureOn) {
  AltCurrentAutoZero z;
  z.begin(kT0);
  EventBatch ev;
  const TimeNs due = kT0 + fromMs(k::AUTO_ZERO_INTERVAL);
  EXPECT_FALSE(z.checkTriggers(at(due, k::AUTO_ZERO_MIN_RPM - 0.1), ev));
  EXPECT_FALSE(z.checkTriggers(at(due, kNoValue), ev));
  AutoZeroInput off = at(due);
  off.enabled = false;
  EXPECT_FALSE(z.checkTriggers(off, ev));
  EXPECT_TRUE(z.checkTriggers(at(due, k::AUTO_ZERO_MIN_RPM), ev));
}

TEST(AltCurrentAutoZero, ATemperatureShiftStartsItEarly) {
  AltCurrentAutoZero z;
  z.begin(kT0);
  EventBatch ev;
  EXPECT_FALSE(z.checkTriggers(at(kT0, 1500.0, 150.0), ev));  // the baseline
  EXPECT_FALSE(z.checkTriggers(at(kT0 + fromSec(60), 1500.0, 150.0 + k::AUTO_ZERO_TEMP_DELTA - 0.1), ev));
  EXPECT_TRUE(z.checkTriggers(at(kT0 + fromSec(61), 1500.0, 150.0 + k::AUTO_ZERO_TEMP_DELTA), ev));
  EXPECT_EQ(ev.items[ev.count - 1].detail, 1) << "detail 1: started by the temperature";
}

// Runs a whole window at 100 ms with a fresh CH1 sample `raw` each tick.
int runWindow(AltCurrentAutoZero& z, TimeNs start, double raw, EventBatch& ev) {
  int activeTicks = 0;
  for (TimeNs t = start; t <= start + fromMs(battery_k::AUTO_ZERO_DURATION_MS); t += fromMs(100)) {
    AutoZeroInput in = at(t);
    in.altCurrentRaw = Reading{raw, t, true};
    if (z.update(in, ev)) ++activeTicks;
  }
  return activeTicks;
}

TEST(AltCurrentAutoZero, TheWindowsMeanBecomesTheZero) {
  AltCurrentAutoZero z;
  z.begin(kT0);
  EventBatch ev;
  const TimeNs start = kT0 + fromMs(k::AUTO_ZERO_INTERVAL);
  ASSERT_TRUE(z.checkTriggers(at(start), ev));
  EXPECT_EQ(runWindow(z, start, 1.25, ev), battery_k::AUTO_ZERO_DURATION_MS / 100);
  EXPECT_FALSE(z.active());
  EXPECT_DOUBLE_EQ(z.zero(), 1.25);
  EXPECT_DOUBLE_EQ(z.corrected(11.25), 10.0);
  EXPECT_EQ(ev.items[ev.count - 1].code, EventCode::AutoZeroDone);
  EXPECT_EQ(ev.items[ev.count - 1].detail, 0);
}

TEST(AltCurrentAutoZero, AMeanAtTheLimitIsTakenAboveItIsRefused) {
  AltCurrentAutoZero at10, above;
  EventBatch ev;
  const TimeNs start = kT0 + fromMs(k::AUTO_ZERO_INTERVAL);
  for (AltCurrentAutoZero* z : {&at10, &above}) {
    z->begin(kT0);
    ASSERT_TRUE(z->checkTriggers(at(start), ev));
  }
  runWindow(at10, start, battery_k::AUTO_ZERO_MAX_OFFSET_A, ev);
  EXPECT_DOUBLE_EQ(at10.zero(), battery_k::AUTO_ZERO_MAX_OFFSET_A);
  runWindow(above, start, battery_k::AUTO_ZERO_MAX_OFFSET_A + 0.01, ev);
  EXPECT_DOUBLE_EQ(above.zero(), 0.0) << "current was really flowing: the old zero stays";
  EXPECT_EQ(ev.items[ev.count - 1].detail, 2);
}

TEST(AltCurrentAutoZero, ResetAndRestore) {
  AltCurrentAutoZero z;
  z.restore(2.5);
  EXPECT_DOUBLE_EQ(z.zero(), 2.5);
  z.reset();
  EXPECT_DOUBLE_EQ(z.zero(), 0.0);
  z.restore(std::nan(""));
  EXPECT_DOUBLE_EQ(z.zero(), 0.0);
  z.restore(50.0);
  EXPECT_DOUBLE_EQ(z.zero(), battery_k::AUTO_ZERO_MAX_OFFSET_A);
}

}  // namespace
}  // namespace xr
