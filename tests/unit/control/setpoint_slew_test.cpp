// SetpointSlew on its own (docs/control.md "Slew Rates and Time Constants"):
// the startup ramp until caught up, the normal rise after it, the fast rise
// inside the window after a protection cleared (and not at its end), the
// unlimited fall under a cap.
#include "control/setpoint_slew.h"

#include <gtest/gtest.h>

namespace xr {
namespace {

SlewInputs asking(double command, TimeNs now, double dt = 0.1) {
  SlewInputs in;
  in.now = now;
  in.dtSec = dt;
  in.command = command;
  in.IBV = 12.5;
  in.ChargingVoltageTarget = 14.4;
  return in;
}

TEST(SetpointSlewPart, StartupRampThenTheNormalRise) {
  Params p;
  SetpointSlew s;
  s.seed(0.0);
  EXPECT_NEAR(s.update(asking(100.0, fromSec(1.0)), p), p.StartupRiseRate * 0.1, 1e-9);
  EXPECT_TRUE(s.inStartupRamp());
  // Caught up with a small command: the ramp ends, the next rise is the normal one.
  s.update(asking(s.setpointLimited(), fromSec(1.1)), p);
  EXPECT_FALSE(s.inStartupRamp());
  const double before = s.setpointLimited();
  EXPECT_NEAR(s.update(asking(100.0, fromSec(1.2)), p) - before, p.SetpointRiseRate * 0.1, 1e-9);
}

TEST(SetpointSlewPart, FastRiseOnlyInsideTheWindowAfterAProtectionCleared) {
  Params p;
  SetpointSlew s;
  s.setLimited(10.0);
  const TimeNs cleared = fromSec(5.0);
  s.onProtectionCleared(cleared);
  const TimeNs lastInside = cleared + fromMs(p.FastSetpointRiseWindowMs) - 1;
  EXPECT_NEAR(s.update(asking(100.0, lastInside), p),
              10.0 + p.SetpointRiseRate * p.FastSetpointRiseRate * 0.1, 1e-9);
  EXPECT_TRUE(s.fastRiseActive());
  const double before = s.setpointLimited();
  EXPECT_NEAR(s.update(asking(100.0, lastInside + 1), p), before + p.SetpointRiseRate * 0.1, 1e-9);
  EXPECT_FALSE(s.fastRiseActive());
}

TEST(SetpointSlewPart, FallsAtTheFallRateUnlessACapActs) {
  Params p;
  SetpointSlew s;
  s.setLimited(80.0);
  EXPECT_NEAR(s.update(asking(0.0, fromSec(1.0)), p), 80.0 - p.SetpointFallRate * 0.1, 1e-9);
  SlewInputs capped = asking(0.0, fromSec(1.1));
  capped.fallUnlimited = true;
  EXPECT_DOUBLE_EQ(s.update(capped, p), 0.0);
  s.setLimited(50.0);
  s.rest();
  EXPECT_DOUBLE_EQ(s.setpointLimited(), 0.0);
  EXPECT_DOUBLE_EQ(s.setpointCommand(), 0.0);
}

}  // namespace
}  // namespace xr
