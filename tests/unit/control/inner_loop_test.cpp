// InnerLoop on its own (docs/control.md "Inner loop", "Governor"): the
// duty climbs at DutyRampRate from the floor, a BMS cap stepping down by
// more than the snap step scales the duty at once (a smaller step does not),
// and a cut leaves everything at zero with the PID in MANUAL.
#include "control/inner_loop.h"

#include <gtest/gtest.h>

namespace xr {
namespace {

InnerInputs asking(double setpoint, double measured, TimeNs now) {
  InnerInputs in;
  in.now = now;
  in.dtSec = 0.1;
  in.input = measured;
  in.setpoint = setpoint;
  in.pidSignal = measured;
  return in;
}

TEST(InnerLoopPart, DutyRisesAtTheRampRateFromTheLastApplied) {
  Params p;
  InnerLoop loop(p);
  loop.track(0.0, 0.0);
  const double d = loop.update(asking(100.0, 0.0, fromSec(1.0)), p);
  EXPECT_LE(d, p.DutyRampRate * 0.1 + 1e-9 + p.MinDuty);
  EXPECT_EQ(loop.pid().mode(), Pid::AUTOMATIC);
  EXPECT_DOUBLE_EQ(loop.lastAppliedDuty(), d);
}

// Holds a duty of 50 % with 40 A flowing under a 60 A cap, then steps the cap.
double dutyAfterCapStep(double newCapA, GovMode* mode) {
  Params p;
  InnerLoop loop(p);
  loop.enterAuto(p, 40.0);
  loop.track(50.0, 50.0);
  InnerInputs in = asking(40.0, 40.0, fromSec(1.0));
  in.bmsCapActive = true;
  in.bmsAltCap = 60.0;
  loop.update(in, p);
  const double before = loop.lastAppliedDuty();
  in.now += fromMs(100);
  in.bmsAltCap = newCapA;
  in.setpoint = newCapA;
  loop.update(in, p);
  *mode = loop.govMode();
  return loop.lastAppliedDuty() / before;
}

TEST(InnerLoopPart, ABmsCapStepSnapsTheDutyASmallerFallDoesNot) {
  GovMode mode = GovMode::GOV_NORMAL_SLEW;
  // 40 A -> 20 A cap: a step (more than the 3 A snap step): duty x 0.5 at once.
  EXPECT_NEAR(dutyAfterCapStep(20.0, &mode), 0.5, 0.02);
  EXPECT_EQ(mode, GovMode::GOV_BYPASS_SLEW);
  // 60 A -> 57.5 A: under the snap step, the PID follows and the slew stays.
  EXPECT_GT(dutyAfterCapStep(57.5, &mode), 0.9);
  EXPECT_EQ(mode, GovMode::GOV_NORMAL_SLEW);
}

TEST(InnerLoopPart, ACutLeavesZeroAndManual) {
  Params p;
  InnerLoop loop(p);
  loop.enterAuto(p, 10.0);
  loop.track(40.0, 40.0);
  loop.cut();
  EXPECT_DOUBLE_EQ(loop.lastAppliedDuty(), 0.0);
  EXPECT_DOUBLE_EQ(loop.dutyRequest(), 0.0);
  EXPECT_DOUBLE_EQ(loop.pid().output, 0.0);
  EXPECT_EQ(loop.pid().mode(), Pid::MANUAL);
}

}  // namespace
}  // namespace xr
