// Detector details the table cannot express: INA228 latch cadences and the
// post-clear disagreement suppression, boot graces, ignore switches, the
// current-stale window in INA slow mode, single-sensor implausibility.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "params/constants.h"
#include "rig.h"

namespace xr::test {
namespace {

using M = FieldControlMode;

TEST(InaLatch, StillAssertedAt3sIsRecheckedEvery10s) {
  Rig r;
  r.warmUp();
  r.inaAlert = true;
  ASSERT_GE(r.runUntil([&] { return r.sup.flags().inaOvervoltageLatched; }, fromMs(300)), 0);
  r.run(fromSec(3.5));  // release check at 3 s finds the alert still asserted
  r.inaAlert = false;
  EXPECT_TRUE(r.sup.flags().inaOvervoltageLatched);
  // Next (definitive) check 10 s after the 3 s one.
  const TimeNs rel = r.runUntil([&] { return !r.sup.flags().inaOvervoltageLatched; }, fromSec(12.0));
  ASSERT_GE(rel, 0);
  EXPECT_NEAR(toSec(rel) + 3.5, 13.0, 0.3);
  EXPECT_EQ(r.count(EventCode::InaLatchCleared), 1u);
}

// A deviation: the alert is looked at on every tick (the chip's alert does not
// latch): one 5 ms tick of it latches; no tick of it does not.
TEST(InaLatch, ShortPulseLatches) {
  Rig r;
  r.warmUp();
  r.inaAlert = true;
  r.tick();
  r.inaAlert = false;
  r.tick();
  EXPECT_TRUE(r.sup.flags().inaOvervoltageLatched);
  EXPECT_EQ(r.d.reason, Reason::REASON_INA_OVERVOLTAGE);
  Rig quiet;
  quiet.warmUp();
  quiet.run(fromSec(1.0));
  EXPECT_FALSE(quiet.sup.flags().inaOvervoltageLatched);
}

// A deviation: T3 that fired is not released by the reading going bad (MANUAL has
// no T5 to stop the field); a usable cooler reading releases it.
TEST(Detectors, T3HeldWhileTheReadingIsStale) {
  Rig r;
  r.manual = true;
  r.warmUp();
  r.tempF = 160.1;  // TemperatureLimitF 150 + TempCritExcess 10
  r.tick();
  ASSERT_EQ(r.d.reason, Reason::REASON_TEMP_CRITICAL);
  r.tempF = -60.0;  // out of range: the sensor died
  r.run(fromSec(2.0));
  EXPECT_TRUE(r.sup.flags().tempCritical);
  EXPECT_EQ(r.d.reason, Reason::REASON_TEMP_CRITICAL);
  r.tempF = 159.9;  // usable and just under: released
  r.tick();
  EXPECT_FALSE(r.sup.flags().tempCritical);
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_MANUAL);
}

TEST(InaLatch, DisagreementSuppressedWhileLatchedAndFor10sAfterClear) {
  Rig r;
  r.warmUp();
  r.inaAlert = true;
  r.batteryV = 12.0;  // sensors diverge as the field collapses
  r.run(fromMs(300));
  r.inaAlert = false;
  ASSERT_GE(r.runUntil([&] { return !r.sup.flags().inaOvervoltageLatched; }, fromSec(4.0)), 0);
  r.run(fromSec(9.9));
  EXPECT_FALSE(r.sup.flags().voltageDisagreeCritical);
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_AUTO_PID);
  // After the 10 s window the check resumes (critical: 1.5 V for 3 s).
  const TimeNs crit = r.runUntil([&] { return r.sup.flags().voltageDisagreeCritical; }, fromSec(5.0));
  EXPECT_NEAR(toSec(crit), 0.1 + 3.0, 0.02);
}

TEST(InaLatch, DisabledWhenInaDisconnected) {
  Params p;
  p.INADisconnected = true;
  Rig r(p);
  r.limp = true;  // one way to run without the INA228 (MANUAL the other)
  r.warmUp();
  r.inaAlert = true;
  r.run(fromSec(1.0));
  EXPECT_FALSE(r.sup.flags().inaOvervoltageLatched);
  EXPECT_EQ(r.d.mode, M::MODE_LIMP_HOME);
}

TEST(Disagreement, NanSensorIsCriticalAtOnce) {
  Rig r;
  r.warmUp();
  r.batteryV = std::numeric_limits<double>::quiet_NaN();
  r.tick();
  EXPECT_EQ(r.d.reason, Reason::REASON_VOLTAGE_DISAGREE_CRITICAL);
  EXPECT_EQ(r.count(EventCode::VoltageDisagreement), 1u);
}

// "Either sensor NaN / < 0.1 V: critical at once": +/-inf and a reading just
// under SENSOR_DEAD_V count as dead too (only NaN was pinned before).
TEST(Disagreement, InfiniteOrNearZeroSensorIsCriticalAtOnce) {
  for (const double v :
       {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0.09, -1.0}) {
    Rig r;
    r.warmUp();
    r.batteryV = v;
    r.tick();
    EXPECT_EQ(r.d.reason, Reason::REASON_VOLTAGE_DISAGREE_CRITICAL) << v;
    EXPECT_EQ(r.count(EventCode::VoltageDisagreement), 1u) << v;
  }
}

TEST(Disagreement, NotJudgedBeforeTheFirstSampleArrivesThenCriticalAfterGrace) {
  Rig q;
  EventBatch ev;
  q.in.IBV = {13.5, q.t, true};
  q.in.BatteryV = Reading{};       // ADS1115 CH0 never answered
  for (int i = 0; i < 300; ++i) {  // 1.5 s
    q.t += kTick;
    q.in.now = q.t;
    q.in.IBV.stamp = q.t;
    q.sup.updateDetectors(q.in, 20.0, ev);
    EXPECT_FALSE(q.sup.flags().voltageDisagreeCritical);
  }
  for (int i = 0; i < 200; ++i) {  // past the 2 s first-sample grace
    q.t += kTick;
    q.in.now = q.t;
    q.in.IBV.stamp = q.t;
    q.sup.updateDetectors(q.in, 20.0, ev);
  }
  EXPECT_TRUE(q.sup.flags().voltageDisagreeCritical);
}

TEST(Implausible, SingleSensorOutOfRangePasses) {
  Rig r;
  r.warmUp();
  r.ibv = 13.5;
  r.batteryV = 16.0;  // only one sensor outside 4.5–15.5 V
  r.tick();
  EXPECT_FALSE(r.sup.flags().voltageImplausible);
  r.ibv = 16.0;
  r.tick();
  EXPECT_TRUE(r.sup.flags().voltageImplausible);
}

TEST(Implausible, RangeScalesWithSystemClass) {
  Params p;
  p.BulkVoltage = 28.8;  // 24 V class: 9.0–30.5 V
  p.AbsorptionVoltage = 28.6;
  Rig r(p);
  r.ibv = r.batteryV = 27.0;
  r.warmUp();
  EXPECT_FALSE(r.sup.flags().voltageImplausible);
  r.ibv = r.batteryV = 8.9;
  r.tick();
  EXPECT_TRUE(r.sup.flags().voltageImplausible);
}

TEST(T5, NeverReadTemperatureGetsA60sBootGrace) {
  Rig r;
  r.freezeTemp = true;  // the sensor never answers
  r.run(fromSec(59.9), fromMs(10));
  EXPECT_FALSE(r.sup.flags().tempStale);
  r.run(fromSec(0.2), fromMs(10));
  EXPECT_TRUE(r.sup.flags().tempStale);
  EXPECT_EQ(r.count(EventCode::TempSensorStale), 1u);
}

TEST(T5, RecoversOnFirstValidReadAfterLockout) {
  Rig r;
  r.warmUp();
  r.freezeTemp = true;
  ASSERT_GE(r.runUntil([&] { return r.sup.flags().lockoutActive; }, fromSec(25.0), fromMs(10)), 0);
  r.freezeTemp = false;
  ASSERT_GE(r.runUntil([&] { return r.d.mode == M::MODE_NORMAL_AUTO_PID; }, fromSec(31.0), fromMs(10)), 0);
}

TEST(IgnoreTemperature, DisablesT1T3ButNotT4T5) {
  Params p;
  p.IgnoreTemperature = true;
  Rig r(p);
  r.warmUp();
  r.tempF = 170.0;
  r.run(fromSec(1.0));
  EXPECT_FALSE(r.sup.flags().tempWarning);
  EXPECT_FALSE(r.sup.flags().tempCritical);
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_AUTO_PID);
  r.freezeTemp = true;
  r.freezeHeartbeat = true;
  r.run(fromSec(21.0), fromMs(10));
  EXPECT_TRUE(r.sup.flags().tempStale);
  EXPECT_TRUE(r.sup.flags().tempTaskAlarm);
}

TEST(IgnoreRpm, DisablesTheGate) {
  Params p;
  p.IgnoreRPM = true;
  Rig r(p);
  r.rpm = 0.0;
  r.warmUp();
  EXPECT_FALSE(r.sup.flags().rpmBelowMin);
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_AUTO_PID);
}

TEST(RpmGate, UnknownRpmCountsAsBelow) {
  Rig r;
  r.rpm = std::numeric_limits<double>::quiet_NaN();
  r.warmUp();
  EXPECT_EQ(r.d.reason, Reason::REASON_RPM_LOW);
  EXPECT_FALSE(r.sc.fieldEnable);
}

TEST(CurrentStale, InaSlowModeIsNotStale) {
  Rig r;
  r.in.inaFastModeActive = false;
  r.warmUp();
  // INA228 slow mode: one sample every ~1.05 s.
  for (int i = 0; i < 10; ++i) {
    r.freezeIna = true;
    r.run(fromMs(1050));
    r.freezeIna = false;
    r.tick();
    EXPECT_FALSE(r.sup.flags().currentStale);
  }
  // Switching to fast mode does not trip on the last slow sample's age.
  r.in.inaFastModeActive = true;
  r.freezeIna = true;
  r.run(fromMs(1000));
  EXPECT_FALSE(r.sup.flags().currentStale);
}

TEST(CurrentStale, InaSilentInFastModeTrips) {
  Rig r;
  r.warmUp();
  r.freezeIna = true;
  const TimeNs took = r.runUntil([&] { return r.sup.flags().currentStale; }, fromSec(1.0));
  EXPECT_NEAR(toSec(took), 0.505, 0.006);
}

TEST(HardOvercurrent, ShortSpikeBelowDebounceDoesNotTrip) {
  Rig r;
  r.warmUp();
  r.altAmps = 100.0;
  r.run(fromMs(15));
  r.altAmps = 20.0;
  r.run(fromMs(100));
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_HARD_OVERCURRENT), 0u);
}

TEST(AutoZero, LockoutRampWithoutAlarmOrLockout) {
  Rig r;
  r.warmUp();
  r.autoZero = true;
  ASSERT_GE(r.runUntil([&] { return !r.sc.fieldEnable; }, fromSec(10.0)), 0);
  EXPECT_EQ(r.d.mode, M::MODE_LOCKOUT_RAMP);
  EXPECT_EQ(r.d.reason, Reason::REASON_AUTO_ZERO);
  EXPECT_FALSE(r.sc.faultAlarm);
  EXPECT_EQ(r.count(EventCode::LockoutStarted), 0u);
  r.autoZero = false;
  r.tick();
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_AUTO_PID);
}

}  // namespace
}  // namespace xr::test

namespace xr::test {
namespace {

// Before the first engine-speed reading the gate holds the field off, but
// files no "RPM below minimum: nan" trip (the false "Engine stopped or
// idling" incident at every start); a first reading that is really low
// trips at once, and a good one leaves no event at all.
TEST(FirstReadings, NoRpmTripBeforeTheFirstReading) {
  Params p;
  p.MinRPMForField = 200.0;
  Rig r(p);
  r.rpm = std::nan("");
  r.run(fromMs(2000));
  EXPECT_TRUE(r.sup.flags().rpmBelowMin) << "the field stays off until a speed is read";
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_RPM_LOW), 0u);
  r.rpm = 1500.0;
  r.run(fromMs(2000));
  EXPECT_FALSE(r.sup.flags().rpmBelowMin);
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_RPM_LOW), 0u);
  EXPECT_EQ(r.count(EventCode::ProtectionClear, Reason::REASON_RPM_LOW), 0u);

  Rig low(p);
  low.rpm = std::nan("");
  low.run(fromMs(500));
  low.rpm = 150.0;  // the first reading, just below the minimum
  low.tick();
  EXPECT_EQ(low.count(EventCode::ProtectionTrip, Reason::REASON_RPM_LOW), 1u);
  Rig atMin(p);
  atMin.rpm = std::nan("");
  atMin.run(fromMs(500));
  atMin.rpm = 200.0;  // at the threshold: allowed
  atMin.tick();
  EXPECT_FALSE(atMin.sup.flags().rpmBelowMin);
  EXPECT_EQ(atMin.count(EventCode::ProtectionTrip, Reason::REASON_RPM_LOW), 0u);
}

// A value hovering on a threshold is one event, not a trip/clear pair per
// tick; the clear is logged once the condition stayed false for the hold.
TEST(EventLogging, DetectorHoveringOnItsThresholdLogsOneTripAndOneClear) {
  Params p;
  p.MinRPMForField = 200.0;
  Rig r(p);
  r.warmUp();
  for (int i = 0; i < 200; ++i) {  // 0.5 s of flapping around the RPM gate
    r.rpm = (i % 2) ? 199.0 : 201.0;
    r.tick(kTick);
  }
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_RPM_LOW), 1u);
  EXPECT_EQ(r.count(EventCode::ProtectionClear, Reason::REASON_RPM_LOW), 0u);
  r.rpm = 1500.0;
  r.run(fromMs(900));
  EXPECT_EQ(r.count(EventCode::ProtectionClear, Reason::REASON_RPM_LOW), 0u) << "cleared before the hold";
  r.run(fromMs(200));
  EXPECT_EQ(r.count(EventCode::ProtectionClear, Reason::REASON_RPM_LOW), 1u);
  r.rpm = 100.0;  // a new trip after the clear is a new event
  r.run(fromMs(50));
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_RPM_LOW), 2u);
}

TEST(EventLogging, BuzzerFollowingAFlappingAlarmLogsOneAlarmOn) {
  Params p;
  p.IgnoreTemperature = true;
  p.MaxTableValue = 200.0;
  Rig r(p);
  r.manual = true;
  r.warmUp();
  for (int i = 0; i < 40; ++i) {  // alternator current toggling across 100 A every 250 ms
    r.altAmps = (i % 2) ? 99.0 : 101.0;
    r.run(fromMs(250));
  }
  EXPECT_EQ(r.count(EventCode::AlarmOn), 1u);
  EXPECT_EQ(r.count(EventCode::AlarmOff), 0u);
  r.altAmps = 20.0;
  r.run(fromSec(29.0));
  EXPECT_FALSE(r.buzzer);
  EXPECT_EQ(r.count(EventCode::AlarmOff), 0u) << "logged before the 30 s throttle";
  r.run(fromSec(1.5));
  EXPECT_EQ(r.count(EventCode::AlarmOff), 1u);
}

// updateTemperature skips its work while nothing can change (same value, no
// older stamps, before the stale / hung deadlines). These pin the edges of
// that shortcut to the full evaluation's results, tick by tick.
TEST(TemperatureQuietPath, StaleTripsOnTheFirstTickPast20sWithAConstantValue) {
  Rig r;
  r.warmUp();
  r.freezeTemp = true;  // the last reading (same value) keeps its stamp
  const TimeNs lastStamp = r.in.AlternatorTemperatureF.stamp;
  r.run(lastStamp + fromMs(k::TEMP_STALE_MS) - r.t, fromMs(10));
  EXPECT_EQ(r.t, lastStamp + fromMs(k::TEMP_STALE_MS));
  EXPECT_FALSE(r.sup.flags().tempStale);  // exactly 20 s old is not stale
  r.tick(fromMs(10));
  EXPECT_TRUE(r.sup.flags().tempStale);
  EXPECT_EQ(r.count(EventCode::TempSensorStale), 1u);
}

TEST(TemperatureQuietPath, HungTripsOnTheFirstTickPast20sWithoutHeartbeat) {
  Rig r;
  r.warmUp();
  r.freezeHeartbeat = true;
  const TimeNs lastBeat = r.in.tempTaskHeartbeat;
  r.run(lastBeat + fromMs(k::TEMP_TASK_TIMEOUT) - r.t, fromMs(10));
  EXPECT_FALSE(r.sup.flags().tempTaskAlarm);
  r.tick(fromMs(10));
  EXPECT_TRUE(r.sup.flags().tempTaskAlarm);
  EXPECT_EQ(r.count(EventCode::TempTaskHung), 1u);
}

TEST(TemperatureQuietPath, NewValueUnderTheSameStampIsJudgedAtOnce) {
  Rig r;
  r.warmUp();
  r.freezeTemp = true;  // stamp stays, only the value changes
  r.in.AlternatorTemperatureF.value = r.p.TemperatureLimitF + r.p.TempCritExcess + 1.0;
  r.tick();
  EXPECT_TRUE(r.sup.flags().tempWarning);
  EXPECT_TRUE(r.sup.flags().tempCritical);
}

TEST(TemperatureQuietPath, ParameterChangeIsJudgedAtOnce) {
  Rig r;
  r.warmUp();
  EXPECT_FALSE(r.sup.flags().tempWarning);
  Params p = r.p;
  p.TemperatureLimitF = r.tempF - p.TempWarnExcess - 1.0;  // the same reading is now above T1
  r.setParams(p);
  r.tick();
  EXPECT_TRUE(r.sup.flags().tempWarning);
  EXPECT_FALSE(r.sup.flags().tempCritical);
}

}  // namespace
}  // namespace xr::test
