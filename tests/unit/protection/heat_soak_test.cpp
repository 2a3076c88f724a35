// Heat soak after an engine stop (a deviation, docs/deviations.md "Heat soak after
// an engine stop", cruising scenario 18): with the engine stopped T1/T2 do
// not count the soak; an engine that restarts above TemperatureLimitF keeps
// the field off (REASON_TEMP_SOAK, no alarm, no lockout) until the case is
// back at the limit. T3 and T5 act as always; a running engine keeps the
// specification's T1/T2 unchanged.
#include <gtest/gtest.h>

#include "rig.h"

namespace xr::test {
namespace {

using M = FieldControlMode;

// Limit 150 F, T1 at 152 F, T3 at 160 F (catalogue defaults).
constexpr double kLimit = 150.0;
constexpr double kWarn = 152.0;

// A rig that ran normally, then stopped its engine for `stoppedS` at tempF.
Rig stoppedHot(double tempF, double stoppedS = 600.0, bool manual = false) {
  Rig r;
  r.manual = manual;
  r.warmUp();
  r.rpm = 0.0;
  r.tempF = tempF;
  r.run(fromSec(stoppedS));
  return r;
}

TEST(HeatSoak, EngineStoppedSoakIsNeitherT1NorT2) {
  // Far longer than TempSustainedTimeout (120 s) above the T1 level.
  Rig r = stoppedHot(kWarn + 3.0);
  EXPECT_FALSE(r.sup.flags().tempWarning);
  EXPECT_FALSE(r.sup.flags().tempSustained);
  EXPECT_EQ(r.d.reason, Reason::REASON_RPM_LOW);
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_TEMP_WARNING), 0u);
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_TEMP_SUSTAINED), 0u);
  // Not announced while the engine is stopped: nothing acts on it yet.
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_TEMP_SOAK), 0u);
}

TEST(HeatSoak, RestartAboveTheLimitHoldsTheFieldUntilItCools) {
  Rig r = stoppedHot(kWarn + 1.7);  // scenario 18: 153.7 F at the restart
  r.rpm = 1800.0;
  r.run(fromSec(1.0));
  EXPECT_EQ(r.d.mode, M::MODE_DISABLED_RAMP);
  EXPECT_EQ(r.d.reason, Reason::REASON_TEMP_SOAK);
  EXPECT_FALSE(r.sup.flags().tempWarning);
  EXPECT_FALSE(r.sup.flags().lockoutActive);
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_TEMP_SOAK), 1u);
  // Held for longer than TempSustainedTimeout: still no T2 (the field is off).
  r.tempF = kWarn + 0.5;
  r.run(fromSec(200.0));
  EXPECT_EQ(r.d.reason, Reason::REASON_TEMP_SOAK);
  EXPECT_FALSE(r.sup.flags().tempSustained);
  // Just above the limit: still held.
  r.tempF = kLimit + 0.1;
  r.run(fromSec(1.0));
  EXPECT_EQ(r.d.reason, Reason::REASON_TEMP_SOAK);
  // At the limit: released, charging resumes, the clear is logged once.
  r.tempF = kLimit;
  r.run(fromSec(1.0));
  EXPECT_FALSE(r.sup.flags().tempSoakHold);
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_AUTO_PID);
  EXPECT_EQ(r.d.reason, Reason::NONE);
  EXPECT_EQ(r.count(EventCode::ProtectionClear, Reason::REASON_TEMP_SOAK), 1u);
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_TEMP_SOAK), 1u);
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_TEMP_WARNING), 0u);
}

TEST(HeatSoak, RestartAtTheLimitIsNoHold) {
  Rig r = stoppedHot(kLimit);
  r.rpm = 1800.0;
  r.run(fromSec(1.0));
  EXPECT_FALSE(r.sup.flags().tempSoakHold);
  EXPECT_EQ(r.d.reason, Reason::NONE);
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_TEMP_SOAK), 0u);
}

TEST(HeatSoak, AfterTheHoldT1AndT2CountAgain) {
  Rig r = stoppedHot(kWarn + 2.0);
  r.rpm = 1800.0;
  r.tempF = kLimit - 1.0;  // cooled: hold released
  r.run(fromSec(1.0));
  ASSERT_EQ(r.d.reason, Reason::NONE);
  r.tempF = kWarn + 0.5;  // the field heats it past T1: the specification's T1
  r.run(fromSec(1.0));
  EXPECT_TRUE(r.sup.flags().tempWarning);
  EXPECT_FALSE(r.sup.flags().tempSoakHold);
  const TimeNs t2 = r.runUntil([&] { return r.sup.flags().tempSustained; }, fromSec(130.0));
  ASSERT_GE(t2, 0);
  EXPECT_NEAR(toSec(t2) + 1.0, r.p.TempSustainedTimeout, 0.05);
}

TEST(HeatSoak, ARunningEngineNeverStartsAHold) {
  Rig r;
  r.warmUp();
  r.tempF = kWarn + 0.1;  // just above T1 with the engine running
  r.run(fromSec(0.1));
  EXPECT_TRUE(r.sup.flags().tempWarning);
  EXPECT_FALSE(r.sup.flags().tempSoakHold);
  EXPECT_EQ(r.d.mode, M::MODE_WARNING_RAMP_AND_LOCKOUT);
  Rig below;
  below.warmUp();
  below.tempF = kWarn;  // at T1's threshold: not above it
  below.run(fromSec(1.0));
  EXPECT_FALSE(below.sup.flags().tempWarning);
  EXPECT_FALSE(below.sup.flags().tempSoakHold);
  EXPECT_EQ(below.d.reason, Reason::NONE);
}

TEST(HeatSoak, T3StillCutsAtTheRestart) {
  Rig r = stoppedHot(kLimit + 10.5);  // above TempCritExcess
  r.rpm = 1800.0;
  r.run(fromSec(0.1));
  EXPECT_EQ(r.d.mode, M::MODE_CRITICAL_RAMP);
  EXPECT_EQ(r.d.reason, Reason::REASON_TEMP_CRITICAL);
}

TEST(HeatSoak, ManualModeIsNotHeldButT3Acts) {
  // T1/T2 are AUTO only, and so is the hold; T3 acts in MANUAL.
  Rig r = stoppedHot(kWarn + 2.0, 600.0, /*manual=*/true);
  r.rpm = 1800.0;
  r.run(fromSec(1.0));
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_MANUAL);
  r.tempF = kLimit + 10.5;
  r.run(fromSec(0.1));
  EXPECT_EQ(r.d.reason, Reason::REASON_TEMP_CRITICAL);
}

TEST(HeatSoak, AStaleReadingEndsTheHoldAndT5Acts) {
  Rig r = stoppedHot(kWarn + 2.0);
  r.rpm = 1800.0;
  r.run(fromSec(1.0));
  ASSERT_EQ(r.d.reason, Reason::REASON_TEMP_SOAK);
  r.freezeTemp = true;  // no fresh reading: T5 after 20 s
  const TimeNs t5 = r.runUntil([&] { return r.d.reason == Reason::REASON_TEMP_STALE; }, fromSec(25.0));
  ASSERT_GE(t5, 0);
  EXPECT_FALSE(r.sup.flags().tempSoakHold);
  EXPECT_EQ(r.d.mode, M::MODE_CRITICAL_RAMP);
}

}  // namespace
}  // namespace xr::test
