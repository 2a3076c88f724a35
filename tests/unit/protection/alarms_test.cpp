// CheckAlarms(): every row of the buzzer table, AlarmActivate, the latch and
// its reset, T4 regardless of AlarmActivate, 30 s throttled messages.
#include <gtest/gtest.h>

#include <cmath>

#include "params/derived.h"
#include "protection/alarm_rows.h"
#include "rig.h"

namespace xr::test {
namespace {

struct AlarmCase {
  const char* name;
  AlarmRow row;
  void (*fire)(Rig&, bool above);
};

const AlarmCase kAlarmCases[] = {
    {"TempHigh", AlarmRow::TempHigh, [](Rig& r, bool a) { r.tempF = a ? 190.1 : 189.9; }},
    {"TempLow", AlarmRow::TempLow, [](Rig& r, bool a) { r.tempF = a ? 31.9 : 32.1; }},
    {"VoltageHigh", AlarmRow::VoltageHigh, [](Rig& r, bool a) { r.ibv = r.batteryV = a ? 15.01 : 14.99; }},
    {"VoltageLow", AlarmRow::VoltageLow, [](Rig& r, bool a) { r.ibv = r.batteryV = a ? 10.99 : 11.01; }},
    {"AltCurrentHigh", AlarmRow::AltCurrentHigh, [](Rig& r, bool a) { r.altAmps = a ? 100.1 : 99.9; }},
    {"BatteryCurrentHigh", AlarmRow::BatteryCurrentHigh,
     [](Rig& r, bool a) { r.bcur = a ? -150.1 : -149.9; }},
    {"InaOvervoltage", AlarmRow::InaOvervoltage, [](Rig& r, bool a) { r.inaAlert = a; }},
    {"EfficiencyAnomaly", AlarmRow::EfficiencyAnomaly, [](Rig& r, bool a) { r.effAnomaly = a; }},
};

class AlarmRowTest : public ::testing::TestWithParam<AlarmCase> {};

// Alarm rows are checked in MANUAL with IgnoreTemperature so the field
// protections (which also sound via the fault-mode row) stay out of the way.
Params alarmParams() {
  Params p;
  p.IgnoreTemperature = true;
  p.MaxTableValue = 200.0;           // hard OC far above the current alarm
  p.CurrentAlarmHigh = 100.0;        // the specification's figure, set (0 derives it from the cap)
  p.AlternatorHardShutdownV = 15.5;  // the hard over-voltage cut (all modes) above the voltage alarm
  return p;
}

TEST_P(AlarmRowTest, SoundsAboveNotBelowAndOnlyWithAlarmActivate) {
  const AlarmCase& c = GetParam();
  {
    Rig r(alarmParams());
    r.manual = true;
    r.warmUp();
    c.fire(r, false);
    r.run(fromSec(1.0));
    EXPECT_FALSE(r.buzzer) << "sounded below threshold";
    c.fire(r, true);
    r.run(fromMs(300));
    EXPECT_TRUE(r.buzzer);
    bool saw = false;
    for (const Event& e : r.log)
      if (e.code == EventCode::AlarmCondition && e.detail == static_cast<int>(c.row)) saw = true;
    EXPECT_TRUE(saw);
  }
  {
    Params p = alarmParams();
    p.AlarmActivate = false;
    Rig r(p);
    r.manual = true;
    r.warmUp();
    c.fire(r, true);
    r.run(fromSec(1.0));
    EXPECT_FALSE(r.buzzer) << "AlarmActivate = 0 must silence this row";
  }
}

INSTANTIATE_TEST_SUITE_P(BuzzerTable, AlarmRowTest, ::testing::ValuesIn(kAlarmCases),
                         [](const ::testing::TestParamInfo<AlarmCase>& i) {
                           return std::string(i.param.name);
                         });

TEST(Alarms, TempSensorNotRespondingAfter20s) {
  Params p;
  Rig r(p);
  r.manual = true;
  r.warmUp();
  r.freezeTemp = true;
  r.run(fromSec(19.5));
  EXPECT_FALSE(r.buzzer);
  r.run(fromSec(1.0));
  EXPECT_TRUE(r.buzzer);
}

TEST(Alarms, TempTaskHangSoundsRegardlessOfAlarmActivate) {
  Params p;
  p.AlarmActivate = false;
  Rig r(p);
  r.manual = true;
  r.warmUp();
  r.freezeHeartbeat = true;
  r.run(fromSec(19.9));
  EXPECT_FALSE(r.buzzer);
  EXPECT_FALSE(r.sup.flags().tempTaskAlarm);
  r.run(fromSec(0.5));
  EXPECT_TRUE(r.sup.flags().tempTaskAlarm);
  EXPECT_TRUE(r.buzzer);
  EXPECT_EQ(r.count(EventCode::TempTaskHung), 1u);
}

TEST(Alarms, LatchHoldsUntilReset) {
  Params p = alarmParams();
  p.AlarmLatchEnabled = true;
  Rig r(p);
  r.manual = true;
  r.warmUp();
  r.altAmps = 120.0;
  r.run(fromMs(300));
  ASSERT_TRUE(r.buzzer);
  r.altAmps = 20.0;
  r.run(fromSec(2.0));
  EXPECT_TRUE(r.buzzer);
  r.sup.resetAlarmLatch();
  r.run(fromMs(300));
  EXPECT_FALSE(r.buzzer);
}

TEST(Alarms, WithoutLatchBuzzerFollowsTheCondition) {
  Rig r(alarmParams());
  r.manual = true;
  r.warmUp();
  r.altAmps = 120.0;
  r.run(fromMs(300));
  ASSERT_TRUE(r.buzzer);
  r.altAmps = 20.0;
  r.run(fromMs(300));
  EXPECT_FALSE(r.buzzer);
}

TEST(Alarms, MessagesThrottledTo30s) {
  Rig r(alarmParams());
  r.manual = true;
  r.warmUp();
  r.altAmps = 120.0;
  r.run(fromSec(65.0), fromMs(10));
  std::size_t n = 0;
  for (const Event& e : r.log)
    if (e.code == EventCode::AlarmCondition && e.detail == static_cast<int>(AlarmRow::AltCurrentHigh)) ++n;
  EXPECT_EQ(n, 3u);  // t = 0, 30, 60 s
}

// A silent BMS sounds the buzzer but files no AlarmCondition row every 30 s:
// its own trip and clear make the one incident.
TEST(Alarms, SilentBmsSoundsWithoutARowEveryThirtySeconds) {
  Rig r(alarmParams());
  r.manual = true;
  r.warmUp();
  r.sup.setBmsStale(true);
  r.run(fromSec(65.0), fromMs(10));
  EXPECT_TRUE(r.buzzer);
  std::size_t n = 0;
  for (const Event& e : r.log)
    n += e.code == EventCode::AlarmCondition && e.detail == static_cast<int>(AlarmRow::BmsStale);
  EXPECT_EQ(n, 0u);
}

TEST(Alarms, TempAlarmLowZeroAndVoltageAlarmLowAtFloorAreOff) {
  Params p = alarmParams();
  p.TempAlarmLow = 0.0;
  p.VoltageAlarmLow = 8.0;  // not above the 8 V floor: row disabled
  Rig r(p);
  r.manual = true;
  r.warmUp();
  r.tempF = -10.0;
  r.ibv = r.batteryV = 7.0;
  r.run(fromSec(1.0));
  EXPECT_FALSE(r.buzzer);
}

TEST(Alarms, StoppedEngineIsNotAnAlarm) {
  Rig r;
  r.warmUp();
  r.rpm = 0.0;
  r.run(fromSec(2.0));
  EXPECT_EQ(r.d.reason, Reason::REASON_RPM_LOW);
  EXPECT_FALSE(r.sc.fieldEnable);
  EXPECT_FALSE(r.buzzer);
}

TEST(Alarms, EvaluatedOnThe250msCadence) {
  Rig r(alarmParams());
  r.manual = true;
  r.warmUp();
  r.altAmps = 120.0;
  const TimeNs took = r.runUntil([&] { return r.buzzer; }, fromSec(1.0));
  EXPECT_GE(took, 0);
  EXPECT_LE(took, fromMs(250));
}

// CurrentAlarmHigh = 0 (the default): 10 % above the most current the
// regulator may command, so holding the cap never sounds it
// (docs/deviations.md "CurrentAlarmHigh follows the cap").
TEST(CurrentAlarmDerived, SitsTenPercentAboveTheCapAndNeverSoundsAtIt) {
  Params p = alarmParams();
  p.CurrentAlarmHigh = 0.0;
  p.MaxTableValue = 120.0;
  for (std::size_t i = 1; i < RPM_TABLE_SIZE; ++i) p.rpmCapCurrentTable[i] = 100.0;
  EXPECT_DOUBLE_EQ(currentAlarmHighAmps(p), 110.0);
  for (const bool above : {false, true}) {
    Rig r(p);
    r.manual = true;
    r.warmUp();
    r.altAmps = above ? 110.1 : 109.9;  // 109.9: over the 100 A cap, under the alarm
    r.run(fromSec(1.0));
    EXPECT_EQ(r.buzzer, above) << r.altAmps;
    bool saw = false;
    for (const Event& e : r.log)
      saw |= e.code == EventCode::AlarmCondition && e.detail == static_cast<int>(AlarmRow::AltCurrentHigh);
    EXPECT_EQ(saw, above) << r.altAmps;
  }
}

}  // namespace
}  // namespace xr::test
