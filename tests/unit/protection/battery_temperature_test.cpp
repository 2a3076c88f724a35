// BatteryTemperatureGuard and the battery temperature orders in mode
// selection (docs/batteries.md): each limit at its threshold, just inside it, with its
// hysteresis, stale, and in each mode.
#include "protection/battery_temperature.h"

#include <gtest/gtest.h>

#include "protection/mode_selection.h"

namespace xr {
namespace {

Params lifepo4() {
  Params p;
  p.ChargeMinTempC = 0.0;
  p.ChargeFullCurrentTempC = 5.0;
  p.ChargeMaxTempC = 45.0;
  p.BatteryTempRequired = true;
  p.BatteryCapacity_Ah = 200.0;
  p.MaximumAllowedBatteryAmps = 100.0;
  return p;
}

struct Rig {
  Params p = lifepo4();
  BatteryTemperatureGuard g;
  TimeNs now = fromSec(10.0);
  EventBatch ev;
  int trips = 0, clears = 0, missing = 0, back = 0;

  const BatteryTempDecision& feed(double tempC, TimeNs stamp,
                                  BatteryTempSource src = BatteryTempSource::ds18b20) {
    Inputs in;
    in.now = now;
    in.batteryTempSource = src;
    in.batteryTempC = {tempC, stamp, stamp == now};
    ev.clear();
    const auto& d = g.update(in, p, ev);
    for (std::size_t i = 0; i < ev.count; ++i) {
      trips += ev.items[i].code == EventCode::ProtectionTrip;
      clears += ev.items[i].code == EventCode::ProtectionClear;
      missing += ev.items[i].code == EventCode::BatteryTempMissing;
      back += ev.items[i].code == EventCode::BatteryTempBack;
    }
    return d;
  }
  const BatteryTempDecision& at(double tempC) {
    now += fromSec(1.0);
    return feed(tempC, now);
  }
};

TEST(BatteryTemperature, ColdLockoutAtThresholdNotJustAboveAndReleasedWithHysteresis) {
  Rig r;
  EXPECT_FALSE(r.at(0.0).cold);     // at ChargeMinTempC: not below it
  EXPECT_TRUE(r.at(-0.0625).cold);  // one DS18B20 step below
  EXPECT_EQ(r.trips, 1);
  EXPECT_TRUE(r.at(0.25).cold);     // inside the 0.5 degC release hysteresis
  EXPECT_TRUE(r.at(-0.0625).cold);  // chatter at the limit: no new trip
  EXPECT_EQ(r.trips, 1);
  EXPECT_FALSE(r.at(0.5).cold);  // ChargeMinTempC + 0.5
  EXPECT_EQ(r.clears, 1);
}

TEST(BatteryTemperature, CurrentCapRampsFromZeroAtMinToFullAtFullCurrentTemp) {
  Rig r;
  EXPECT_DOUBLE_EQ(r.at(0.0).currentCapA, 0.0);
  EXPECT_DOUBLE_EQ(r.at(2.5).currentCapA, 50.0);
  EXPECT_DOUBLE_EQ(r.at(4.9).currentCapA, 98.0);
  EXPECT_EQ(r.at(5.0).currentCapA, 1e300);  // full current: no cap of its own
  EXPECT_EQ(r.at(25.0).currentCapA, 1e300);
}

TEST(BatteryTemperature, HotStopAboveMaxResumesOnly3DegreesBelow) {
  Rig r;
  EXPECT_FALSE(r.at(45.0).hot);  // at the limit
  EXPECT_TRUE(r.at(45.0625).hot);
  EXPECT_TRUE(r.at(42.1).hot);   // 2.9 degC below: still stopped
  EXPECT_FALSE(r.at(42.0).hot);  // 3 degC below: resumes
  EXPECT_EQ(r.trips, 1);
  EXPECT_EQ(r.clears, 1);
}

TEST(BatteryTemperature, StaleSampleCapsAtC10WhenRequiredWithOneWarning) {
  Rig r;
  EXPECT_TRUE(r.at(20.0).known);
  const TimeNs last = r.now;
  // Just inside the 20 s stale limit: still known.
  r.now = last + fromMs(20000);
  EXPECT_TRUE(r.feed(20.0, last).known);
  // Just past it: C/10 of 200 Ah, one warning however long it lasts.
  for (int i = 1; i <= 50; ++i) {
    r.now = last + fromMs(20000 + i * 100);
    const auto& d = r.feed(20.0, last);
    EXPECT_FALSE(d.known);
    EXPECT_DOUBLE_EQ(d.currentCapA, 20.0);
  }
  EXPECT_EQ(r.missing, 1);
  EXPECT_DOUBLE_EQ(r.at(20.0).currentCapA, 1e300);
  EXPECT_EQ(r.back, 1);
}

TEST(BatteryTemperature, WithoutTemperatureRequiredTheBankChargesUncappedWithAWarning) {
  Rig r;
  r.p.BatteryTempRequired = false;
  r.p.TempCompMvPerCellC = -4.0;  // lead-acid: charges uncompensated
  r.now += fromSec(10.0);
  const auto& d = r.feed(kNoValue, 0, BatteryTempSource::none);  // no sensor configured
  EXPECT_EQ(d.currentCapA, 1e300);
  EXPECT_EQ(r.missing, 1);
}

TEST(BatteryTemperature, NoSourceAndNothingDependingOnItIsSilent) {
  Rig r;
  r.p = Params{};  // custom defaults: no compensation, not required
  for (int i = 0; i < 10; ++i) r.feed(kNoValue, 0, BatteryTempSource::none);
  EXPECT_EQ(r.missing, 0);
  EXPECT_EQ(r.g.decision().currentCapA, 1e300);
}

TEST(BatteryTemperature, AConfiguredSourceGetsTimeForItsFirstSampleAtZeroCurrent) {
  Rig r;
  const TimeNs start = r.now;
  EXPECT_DOUBLE_EQ(r.feed(kNoValue, 0).currentCapA, 0.0);
  r.now = start + fromMs(4900);
  EXPECT_DOUBLE_EQ(r.feed(kNoValue, 0).currentCapA, 0.0);
  EXPECT_EQ(r.missing, 0);
  r.now = start + fromMs(5000);
  EXPECT_DOUBLE_EQ(r.feed(kNoValue, 0).currentCapA, 20.0);
  EXPECT_EQ(r.missing, 1);
}

TEST(BatteryTemperature, OutOfRangeValueIsNotATemperature) {
  Rig r;
  EXPECT_FALSE(r.at(126.0).known);
  EXPECT_FALSE(r.at(126.0).hot);
}

TEST(BatteryTemperature, ColdAndHotAreOrdersInEveryModeLikeTheBms) {
  for (bool cold : {true, false}) {
    TickSnapshot s;
    s.batteryCold = cold;
    s.batteryHot = !cold;
    const Reason want = cold ? Reason::REASON_BATTERY_COLD : Reason::REASON_BATTERY_HOT;
    EXPECT_EQ(selectFieldMode(s).mode, FieldControlMode::MODE_DISABLED_RAMP);
    EXPECT_EQ(selectFieldMode(s).reason, want);
    s.manualMode = true;
    EXPECT_EQ(selectFieldMode(s).reason, want);
    s.limpHome = true;
    EXPECT_EQ(selectFieldMode(s).mode, FieldControlMode::MODE_DISABLED_RAMP);
    EXPECT_EQ(selectFieldMode(s).reason, want);
  }
  // A fault of higher priority still names itself.
  TickSnapshot s;
  s.batteryCold = true;
  s.prot.hardOvercurrent = true;
  EXPECT_EQ(selectFieldMode(s).reason, Reason::REASON_HARD_OVERCURRENT);
  EXPECT_FALSE(isImmediateCutReason(Reason::REASON_BATTERY_COLD));  // a clean ramp, not a cut
}

TEST(BatteryTemperature, EventsReadAsSentences) {
  EXPECT_EQ(describe(makeEvent(0, EventLevel::Warning, EventCode::ProtectionTrip, Reason::REASON_BATTERY_COLD,
                               -5, 0)),
            "Battery too cold to charge: -5.0 C < 0.0 C. Field off until it warms");
  EXPECT_EQ(
      describe(makeEvent(0, EventLevel::Warning, EventCode::BatteryTempMissing, Reason::NONE, 20, 0, 1)),
      "Battery temperature missing or stale: charge current capped at C/10 (20.0 A) (BatteryTempRequired)");
}

}  // namespace
}  // namespace xr
