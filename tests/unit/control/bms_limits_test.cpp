// A BMS's charge limits (docs/integrations.md): the BmsLimiter on its own, then the whole
// Regulator against the test plant following CCL, CVL, charge-disable,
// warnings and a silent BMS.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "control/bms_limiter.h"
#include "reg_rig.h"

namespace xr {
namespace {

Params bmsParams() {
  Params p;
  p.BmsLimitsEnabled = true;
  return p;
}

BmsLimits limits(TimeNs stamp, double cvl, double ccl) {
  BmsLimits b;
  b.cvlV = cvl;
  b.cclA = ccl;
  b.dclA = 100;
  b.socPct = 60;
  b.source = BmsSource::Can;
  b.stamp = stamp;
  return b;
}

// What the CAN service posts when a BMS bus is configured: never heard.
BmsLimits canConfigured() {
  BmsLimits b;
  b.source = BmsSource::Can;
  return b;
}

int countReason(const EventBatch& ev, EventCode code, Reason r) {
  int n = 0;
  for (std::size_t i = 0; i < ev.count; ++i) n += ev.items[i].code == code && ev.items[i].reason == r;
  return n;
}

constexpr double kNoPackV = std::numeric_limits<double>::quiet_NaN();

TEST(BmsLimiter, ConfiguredSourceIsFollowedByDefault) {
  const Params p;  // nothing set: the catalogue's defaults
  ASSERT_TRUE(p.BmsLimitsEnabled);
  BmsLimiter l;
  EventBatch ev;
  l.update(limits(fromSec(1), 14.0, 20), fromSec(1), 30, kNoPackV, p, ev);
  EXPECT_EQ(l.state(), BmsState::OK);
  EXPECT_DOUBLE_EQ(l.batteryCapA(), 20.0);
}

TEST(BmsLimiter, NoSourceConfiguredIsOffAndNeverStale) {
  const Params p;
  BmsLimiter l;
  EventBatch ev;
  const BmsLimits none;  // source None: no BMS on CAN, no Victron GX
  l.update(none, fromSec(1), 30, kNoPackV, p, ev);
  l.update(none, fromSec(600), 30, kNoPackV, p, ev);
  EXPECT_EQ(l.state(), BmsState::OFF);
  EXPECT_TRUE(std::isinf(l.batteryCapA()));
  EXPECT_EQ(ev.count, 0u);
}

TEST(BmsLimiter, SilentConfiguredSourceIsStaleWithDefaultParams) {
  const Params p;  // BmsStaleS = 5 s
  BmsLimiter l;
  EventBatch ev;
  BmsLimits configured;  // what the CAN service posts when the bus is set: never heard
  configured.source = BmsSource::Can;
  l.update(configured, fromSec(10), 30, kNoPackV, p, ev);
  l.update(configured, fromSec(15), 30, kNoPackV, p, ev);
  EXPECT_FALSE(l.stale());  // exactly BmsStaleS: not yet
  l.update(configured, fromSec(15) + 1, 30, kNoPackV, p, ev);
  EXPECT_TRUE(l.stale());
  EXPECT_DOUBLE_EQ(l.batteryCapA(), p.BmsFallbackCapA);
}

TEST(BmsLimiter, MonitorOnlyCapsNothingEvenWithLimits) {
  BmsLimiter l;
  EventBatch ev;
  Params p;
  p.BmsLimitsEnabled = false;  // monitor only, the owner's explicit choice
  l.update(limits(fromSec(1), 14.0, 20), fromSec(1), 30, kNoPackV, p, ev);
  EXPECT_EQ(l.state(), BmsState::OFF);
  EXPECT_TRUE(std::isinf(l.batteryCapA()));
  EXPECT_TRUE(std::isinf(l.cvlCeilingV()));
  EXPECT_TRUE(l.chargeAllowed());
}

TEST(BmsLimiter, FreshLimitsCapBatteryCurrentAndVoltage) {
  BmsLimiter l;
  EventBatch ev;
  Params p = bmsParams();
  p.BmsCvlMarginV = 0.05;
  l.update(limits(fromSec(1), 14.0, 20), fromSec(1), 30, kNoPackV, p, ev);
  EXPECT_EQ(l.state(), BmsState::OK);
  EXPECT_DOUBLE_EQ(l.batteryCapA(), 20.0);
  EXPECT_NEAR(l.cvlCeilingV(), 13.95, 1e-12);
  EXPECT_DOUBLE_EQ(l.shownCclA(), 20.0);
  EXPECT_DOUBLE_EQ(l.shownSocPct(), 60.0);
}

TEST(BmsLimiter, StaleAtBmsStaleSNotJustBelow) {
  BmsLimiter l;
  EventBatch ev;
  const Params p = bmsParams();  // BmsStaleS = 5
  const BmsLimits b = limits(fromSec(10), 14.0, 40);
  l.update(b, fromSec(10), 0, kNoPackV, p, ev);
  ev.clear();
  l.update(b, fromSec(15), 0, kNoPackV, p, ev);  // exactly 5 s: not yet
  EXPECT_FALSE(l.stale());
  EXPECT_EQ(countReason(ev, EventCode::ProtectionTrip, Reason::REASON_BMS_STALE), 0);
  l.update(b, fromSec(15) + fromMs(1), 0, kNoPackV, p, ev);
  EXPECT_TRUE(l.stale());
  EXPECT_EQ(l.state(), BmsState::STALE);
  EXPECT_DOUBLE_EQ(l.batteryCapA(), p.BmsFallbackCapA);
  EXPECT_TRUE(std::isinf(l.cvlCeilingV()));  // the stage voltages apply again
  EXPECT_TRUE(std::isnan(l.shownCclA()));
  EXPECT_EQ(countReason(ev, EventCode::ProtectionTrip, Reason::REASON_BMS_STALE), 1);
  ev.clear();
  l.update(b, fromSec(16), 0, kNoPackV, p, ev);  // one event per edge
  EXPECT_EQ(countReason(ev, EventCode::ProtectionTrip, Reason::REASON_BMS_STALE), 0);
  l.update(limits(fromSec(17), 14.0, 40), fromSec(17), 0, kNoPackV, p, ev);
  EXPECT_FALSE(l.stale());
  EXPECT_DOUBLE_EQ(l.batteryCapA(), 40.0);
  EXPECT_EQ(countReason(ev, EventCode::ProtectionClear, Reason::REASON_BMS_STALE), 1);
}

TEST(BmsLimiter, NeverHeardIsStaleAfterBmsStaleS) {
  BmsLimiter l;
  EventBatch ev;
  const Params p = bmsParams();
  l.update(canConfigured(), fromSec(2), 0, kNoPackV, p, ev);
  EXPECT_FALSE(l.stale());
  l.update(canConfigured(), fromSec(7), 0, kNoPackV, p, ev);
  EXPECT_FALSE(l.stale());
  l.update(canConfigured(), fromSec(7) + fromMs(10), 0, kNoPackV, p, ev);
  EXPECT_TRUE(l.stale());
}

TEST(BmsLimiter, WarningRampsFromPresentCurrentToZeroAndBack) {
  BmsLimiter l;
  EventBatch ev;
  Params p = bmsParams();
  p.BmsWarnRampS = 2.0;
  TimeNs t = fromSec(1);
  BmsLimits b = limits(t, 14.2, 80);
  l.update(b, t, 40, kNoPackV, p, ev);
  EXPECT_DOUBLE_EQ(l.batteryCapA(), 80.0);
  b.warnings = bmswarn::HighVoltage;
  t += fromMs(100);
  b.stamp = t;
  l.update(b, t, 40, kNoPackV, p, ev);  // from the 40 A flowing now, at 40 A / 2 s: less 0.1 s x 20 A/s
  EXPECT_EQ(l.state(), BmsState::WARNING);
  EXPECT_NEAR(l.batteryCapA(), 38.0, 1e-9);
  t += fromSec(1);
  b.stamp = t;
  l.update(b, t, 38, kNoPackV, p, ev);
  EXPECT_NEAR(l.batteryCapA(), 18.0, 1e-9);
  t += fromSec(1);
  b.stamp = t;
  l.update(b, t, 20, kNoPackV, p, ev);
  EXPECT_DOUBLE_EQ(l.batteryCapA(), 0.0);  // 0 within BmsWarnRampS of the warning
  b.warnings = bmswarn::CellImbalance;     // shown only: the ramp goes back up
  t += fromSec(1);
  b.stamp = t;
  l.update(b, t, 0, kNoPackV, p, ev);
  EXPECT_NEAR(l.batteryCapA(), 20.0, 1e-9);
  EXPECT_EQ(l.state(), BmsState::OK);
  t += fromSec(4);
  b.stamp = t;
  l.update(b, t, 20, kNoPackV, p, ev);
  EXPECT_DOUBLE_EQ(l.batteryCapA(), 80.0);  // back at CCL: the ramp is over
}

TEST(BmsLimiter, HighCellHoldsAPackCeilingFromBmsCellHighV) {
  BmsLimiter l;
  EventBatch ev;
  Params p = bmsParams();  // BmsCellHighV = 3.60
  p.BatteryCells = 4;
  ASSERT_DOUBLE_EQ(p.BmsCellHighV, 3.60);
  BmsLimits b = limits(fromSec(1), 14.2, 50);
  b.cellMaxV = 3.599;  // just below: nothing holds the pack
  l.update(b, fromSec(1), 40, 13.9, p, ev);
  EXPECT_FALSE(l.cellHigh());
  EXPECT_DOUBLE_EQ(l.cvlCeilingV(), 14.2);
  b.cellMaxV = 3.600;  // at the limit: the ceiling starts at the pack voltage, no step
  l.update(b, fromSec(1) + fromMs(100), 40, 13.9, p, ev);
  EXPECT_TRUE(l.cellHigh());
  EXPECT_NEAR(l.cvlCeilingV(), 13.9, 1e-9);
  EXPECT_EQ(l.state(), BmsState::OK);       // not a warning: no ramp to zero
  EXPECT_DOUBLE_EQ(l.batteryCapA(), 50.0);  // the current is not cut
  b.cellMaxV = 3.620;  // 20 mV over: the ceiling falls at 4 cells x 20 mV / 20 s = 4 mV/s
  l.update(b, fromSec(2) + fromMs(100), 40, 13.9, p, ev);
  EXPECT_NEAR(l.cvlCeilingV(), 13.9 - 0.004, 1e-9);
  b.cellMaxV = 3.590;  // under: it rises again, 2 mV/s
  l.update(b, fromSec(3) + fromMs(100), 40, 13.9, p, ev);
  EXPECT_NEAR(l.cvlCeilingV(), 13.9 - 0.004 + 0.002, 1e-9);
  // A tick without a pack voltage: the ceiling holds, it is not dropped.
  const double held = l.cvlCeilingV();
  l.update(b, fromSec(3) + fromMs(200), 40, kNoPackV, p, ev);
  EXPECT_TRUE(l.cellHigh());
  EXPECT_DOUBLE_EQ(l.cvlCeilingV(), held);
  // Far over for long: the ceiling never goes more than 0.3 V under the pack.
  b.cellMaxV = 3.9;
  b.stamp = fromSec(60);  // the BMS keeps talking
  l.update(b, fromSec(60), 40, 13.8, p, ev);
  EXPECT_NEAR(l.cvlCeilingV(), 13.5, 1e-9);
  // Once the ceiling is 0.2 V over the pack nothing holds it: released.
  b.cellMaxV = 3.3;
  b.stamp = fromSec(200);
  l.update(b, fromSec(200), 0, 13.3, p, ev);
  EXPECT_FALSE(l.cellHigh());
  EXPECT_DOUBLE_EQ(l.cvlCeilingV(), 14.2);
}

TEST(BmsLimiter, HighCellCeilingOffWithoutCellVoltagesOrAtZero) {
  EventBatch ev;
  BmsLimits b = limits(fromSec(1), 14.2, 50);
  Params off = bmsParams();
  off.BmsCellHighV = 0.0;
  BmsLimiter l2;
  b.cellMaxV = 4.0;
  l2.update(b, fromSec(3), 40, 14.0, off, ev);
  EXPECT_FALSE(l2.cellHigh());
  EXPECT_DOUBLE_EQ(l2.cvlCeilingV(), 14.2);
  BmsLimiter l3;
  b.cellMaxV = kBmsNoValue;
  l3.update(b, fromSec(3), 40, 14.0, bmsParams(), ev);
  EXPECT_FALSE(l3.cellHigh());
  EXPECT_EQ(l3.state(), BmsState::OK);
}

TEST(BmsLimiter, CellsInSeriesFromThePackWhenNotConfigured) {
  // A custom profile leaves BatteryCells at 0: 27.2 V over a 3.4 V mean cell
  // is 8 cells, so 20 mV over the limit lowers the ceiling 8 mV/s.
  BmsLimiter l;
  EventBatch ev;
  Params p = bmsParams();
  ASSERT_EQ(p.BatteryCells, 0);
  p.BulkVoltage = 28.4;  // the 24 V class: the CVL and the cells fit the bank
  BmsLimits b = limits(fromSec(1), 28.4, 50);
  b.cellMaxV = 3.60;
  b.cellMinV = 3.20;
  l.update(b, fromSec(1), 40, 27.2, p, ev);
  b.cellMaxV = 3.62;
  l.update(b, fromSec(2), 40, 27.2, p, ev);
  EXPECT_NEAR(l.cvlCeilingV(), 27.2 - 0.008, 1e-9);
}

TEST(BmsLimiter, ChargeDisableFlagIsPassedOn) {
  BmsLimiter l;
  EventBatch ev;
  BmsLimits b = limits(fromSec(1), 14.0, 40);
  b.chargeAllowed = false;
  l.update(b, fromSec(1), 0, kNoPackV, bmsParams(), ev);
  EXPECT_FALSE(l.chargeAllowed());
  EXPECT_EQ(l.state(), BmsState::CHARGE_DISABLED);
}

// ---- closed loop: the Regulator against the test plant --------------------

struct BmsLoop : test::RegRig {
  BmsLoop() : RegRig(bmsParams()) {
    plant.house = 8.0;
    plant.ampsPerPct = 1.0;
    bms = limits(now, 15.0, 100.0);
  }
  // Runs `seconds` with the BMS repeating its limits every 0.5 s; returns the
  // largest battery current seen after `settleS`.
  double run(double seconds, double settleS = 0.0, bool talking = true) {
    double worst = -1e9;
    const long n = std::lround(seconds / 0.0025);
    for (long i = 0; i < n; ++i) {
      if (talking && now - bms.stamp >= fromMs(500)) bms.stamp = now;
      tick();
      if (i * 0.0025 >= settleS) worst = std::max(worst, plant.Ibat());
    }
    return worst;
  }
};

TEST(BmsClosedLoop, BatteryCurrentFollowsACclStepWithinOneSecond) {
  BmsLoop r;
  r.plant.Vocv = 12.6;  // far from any voltage target: pure current limit
  r.bms.cclA = 40;
  r.run(30);
  EXPECT_GT(r.plant.Ibat(), 30.0);  // the cap table (50 A) less the house: ~42 A, CCL 40 binds
  EXPECT_LE(r.plant.Ibat(), 42.0);
  r.bms.cclA = 10;
  r.bms.stamp = r.now;
  const double worstAfter1s = r.run(5, 1.0);
  EXPECT_LE(worstAfter1s, 12.0);
  EXPECT_GT(r.plant.Ibat(), 7.0);  // capped, not stopped: the house is still served
  EXPECT_GT(r.plant.Ialt, r.plant.house);
  EXPECT_NEAR(r.out->telemetry.bms_ccl_a, 10.0, 1e-12);
  EXPECT_EQ(r.out->telemetry.bms_state, BmsState::OK);
}

TEST(BmsClosedLoop, VoltageHeldAtCvlBelowTheStageTarget) {
  BmsLoop r;
  r.plant.Vocv = 13.5;
  r.bms.cvlV = 13.8;  // under BulkVoltage 14.5 and AbsorptionVoltage 14.4
  r.run(20);
  double worst = 0;
  for (int i = 0; i < 40000; ++i) {
    if (r.now - r.bms.stamp >= fromMs(500)) r.bms.stamp = r.now;
    r.tick();
    worst = std::max(worst, r.plant.V());
  }
  EXPECT_LE(worst, 13.8 + 0.02);
  EXPECT_GT(r.plant.V(), 13.7);  // held at CVL, not stopped short
  EXPECT_NEAR(r.out->telemetry.target_v, 13.8, 1e-9);
}

TEST(BmsClosedLoop, ChargeDisableTurnsTheFieldOffWithBmsDisabled) {
  BmsLoop r;
  r.plant.Vocv = 12.6;
  r.run(10);
  EXPECT_TRUE(r.out->fieldEnable);
  r.bms.chargeAllowed = false;
  r.run(10);
  EXPECT_FALSE(r.out->fieldEnable);
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_BMS_DISABLED);
  EXPECT_EQ(r.out->telemetry.bms_state, BmsState::CHARGE_DISABLED);
}

TEST(BmsClosedLoop, WarningRampsTheChargeDownSmoothly) {
  BmsLoop r;
  r.plant.Vocv = 12.6;
  r.run(30);
  const double before = r.plant.Ibat();
  ASSERT_GT(before, 30.0);
  r.bms.warnings = bmswarn::HighVoltage;
  // Smooth: half-way through BmsWarnRampS (1 s) the current is falling, not cut.
  r.run(0.5);
  EXPECT_GT(r.plant.Ibat(), 10.0);
  EXPECT_LT(r.plant.Ibat(), before - 4.0);
  r.run(2.0);  // the cap reached 0 after 1 s; the loop follows it down
  EXPECT_LE(r.plant.Ibat(), 2.0);
  EXPECT_EQ(r.out->telemetry.bms_state, BmsState::WARNING);
}

TEST(BmsClosedLoop, SilentBmsFallsBackWithinBmsStaleSPlusOne) {
  BmsLoop r;
  r.plant.Vocv = 12.6;
  r.run(30);
  ASSERT_GT(r.plant.Ibat(), 30.0);
  EXPECT_EQ(r.out->telemetry.reason, Reason::NONE);
  const double worst = r.run(r.p.BmsStaleS + 1.0 + 5.0, r.p.BmsStaleS + 1.0, /*talking=*/false);
  EXPECT_LE(worst, r.p.BmsFallbackCapA + 2.0);
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_BMS_STALE);
  EXPECT_EQ(r.out->telemetry.bms_state, BmsState::STALE);
  EXPECT_TRUE(std::isnan(r.out->telemetry.bms_ccl_a));
  EXPECT_TRUE(r.out->fieldEnable);  // a cap, not a shutdown
}

TEST(BmsClosedLoop, StaleRaisesTheAlarmWhenAlarmsAreOn) {
  Params p = bmsParams();
  p.AlarmActivate = true;
  test::RegRig r(p);
  r.bms = canConfigured();  // a BMS on CAN is configured and never speaks
  r.plant.Vocv = 12.6;
  r.run(2);
  EXPECT_FALSE(r.out->buzzer);
  r.run(5);  // never heard: stale after BmsStaleS
  EXPECT_TRUE(r.out->buzzer);
}

// The whole regulator: a BMS that holds the charge (CCL 0) with the engine
// running and the bank not full is told after 15 min, naming the BMS, with
// the alarm; not at 14 min 59 s.
TEST(BmsClosedLoop, AChargeHeldByTheBmsFor15MinIsOneAlarmNamingIt) {
  BmsLoop r;
  r.plant.Vocv = 12.6;
  r.bms.cclA = 0;
  int held = 0;
  auto runCounting = [&](double seconds) {
    const long n = std::lround(seconds / 0.0025);
    for (long i = 0; i < n; ++i) {
      if (r.now - r.bms.stamp >= fromMs(500)) r.bms.stamp = r.now;
      const Outputs& o = r.tick();
      for (std::size_t k = 0; k < o.events.count; ++k)
        if (o.events.items[k].code == EventCode::ChargingHeld) {
          ++held;
          EXPECT_EQ(static_cast<ChargeHold>(o.events.items[k].detail), ChargeHold::BMS);
        }
    }
  };
  runCounting(898.0);
  EXPECT_EQ(held, 0);
  EXPECT_EQ(r.out->telemetry.charge_held_by, ChargeHold::BMS);  // shown before the alarm
  EXPECT_FALSE(r.out->buzzer);
  runCounting(4.0);
  EXPECT_EQ(held, 1);
  EXPECT_TRUE(r.out->buzzer);
  EXPECT_GE(r.out->telemetry.charge_held_min, 15.0);
  // The BMS lets go: charging again, and a minute later the episode ends.
  r.bms.cclA = 100;
  runCounting(70.0);
  EXPECT_EQ(held, 2);
  EXPECT_EQ(r.out->telemetry.charge_held_by, ChargeHold::NONE);
}

}  // namespace
}  // namespace xr
