// FieldRest on its own (docs/deviations.md "Full bank at light load"): a
// rest starts only after the condition held FieldRestDelayMs, not just
// before; a break in the condition restarts the count; it ends when the bank
// falls FieldRestWakeV under the target, not at the target.
#include "control/field_rest.h"

#include <gtest/gtest.h>

namespace xr {
namespace {

RestInputs fullBankAtTheFloor(const Params& p, TimeNs now) {
  RestInputs r;
  r.now = now;
  r.voltageControlActive = true;
  r.ChargingVoltageTarget = 13.5;
  r.IBV = 13.5 + p.FieldRestMarginV + 0.01;
  r.rpmMinDuty = 20.0;
  r.dutyRequest = 20.0;  // at the floor
  r.setpointCommand = 5.0;
  return r;
}

TEST(FieldRestPart, StartsAfterTheDelayNotJustBefore) {
  Params p;
  FieldRest rest;
  const TimeNs t0 = fromSec(10.0);
  EXPECT_FALSE(rest.startDue(fullBankAtTheFloor(p, t0), p));
  EXPECT_FALSE(rest.startDue(fullBankAtTheFloor(p, t0 + fromMs(p.FieldRestDelayMs) - 1), p));
  EXPECT_FALSE(rest.resting());
  EXPECT_TRUE(rest.startDue(fullBankAtTheFloor(p, t0 + fromMs(p.FieldRestDelayMs)), p));
  EXPECT_TRUE(rest.resting());
}

TEST(FieldRestPart, ABreakInTheConditionRestartsTheCount) {
  Params p;
  FieldRest rest;
  const TimeNs t0 = fromSec(10.0);
  rest.startDue(fullBankAtTheFloor(p, t0), p);
  RestInputs under = fullBankAtTheFloor(p, t0 + fromMs(p.FieldRestDelayMs / 2));
  under.IBV = 13.5 + p.FieldRestMarginV - 0.01;  // just under the margin
  EXPECT_FALSE(rest.startDue(under, p));
  EXPECT_FALSE(rest.startDue(fullBankAtTheFloor(p, t0 + fromMs(p.FieldRestDelayMs)), p));
  EXPECT_FALSE(rest.resting());
}

TEST(FieldRestPart, NoRestWhileATuningRunOwnsTheField) {
  Params p;
  FieldRest rest;
  RestInputs r = fullBankAtTheFloor(p, fromSec(10.0));
  r.tuningActive = true;
  rest.startDue(r, p);
  r.now += fromMs(p.FieldRestDelayMs);
  EXPECT_FALSE(rest.startDue(r, p));
}

TEST(FieldRestPart, EndsUnderTheWakeBandAndOnLeavingAuto) {
  Params p;
  FieldRest rest;
  const TimeNs t0 = fromSec(10.0);
  rest.startDue(fullBankAtTheFloor(p, t0), p);
  ASSERT_TRUE(rest.startDue(fullBankAtTheFloor(p, t0 + fromMs(p.FieldRestDelayMs)), p));
  RestInputs r = fullBankAtTheFloor(p, t0 + fromSec(60.0));
  r.IBV = 13.5 - p.FieldRestWakeV + 0.01;  // just above the wake band
  EXPECT_FALSE(rest.endDue(r, p));
  EXPECT_TRUE(rest.resting());
  r.IBV = 13.5 - p.FieldRestWakeV - 0.01;
  EXPECT_TRUE(rest.endDue(r, p));
  EXPECT_FALSE(rest.resting());
  rest.startDue(fullBankAtTheFloor(p, t0 + fromSec(70.0)), p);
  ASSERT_TRUE(rest.startDue(fullBankAtTheFloor(p, t0 + fromSec(70.0) + fromMs(p.FieldRestDelayMs)), p));
  rest.leave();
  EXPECT_FALSE(rest.resting());
}

}  // namespace
}  // namespace xr
