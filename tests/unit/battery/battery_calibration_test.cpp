// Full-charge detection, auto shunt-gain correction and the alternator
// current auto-zero (docs/batteries.md).
#include <gtest/gtest.h>

#include <cmath>

#include "battery_fixture.h"
#include "params/constants.h"

namespace xr {
namespace {

using test::BatteryRig;

Params calParams() {
  Params p;
  p.BatteryCapacity_Ah = 200.0;
  p.ChargeEfficiency = 100.0;
  p.PeukertExponent = 1.0;
  p.SOCUpdateInterval = 2000;
  p.ChargedVoltage = 13.8;
  p.ChargedDetectionTime = 60.0;
  p.TailCurrent = 2.0;  // 4 A on 200 Ah
  p.AutoShuntGainCorrection = true;
  return p;
}

// Holds full-charge conditions until detection; returns seconds it took.
double holdFull(BatteryRig& r, double maxSeconds = 200.0) {
  r.ina(14.0, 1.0);
  for (double t = 0.0; t < maxSeconds; t += 1.0) {
    r.tick(1.0);
    if (r.sawEvent(EventCode::FullChargeDetected)) return t + 1.0;
  }
  return -1.0;
}

TEST(FullCharge, DetectedAfterChargedDetectionTime) {
  BatteryRig r(calParams());
  r.mon.setSoc(80.0);
  r.ina(13.0, 30.0);
  r.run(10.0, 1.0);
  EXPECT_FALSE(r.mon.fullChargeDetected());
  const double took = holdFull(r);
  // Granularity is one SOCUpdateInterval (2 s).
  EXPECT_GE(took, 60.0 - 2.0);
  EXPECT_LE(took, 60.0 + 2.0);
  EXPECT_TRUE(r.mon.fullChargeDetected());
  EXPECT_DOUBLE_EQ(r.mon.socPercent(), 100.0);
}

TEST(FullCharge, InterruptedConditionRestartsTimer) {
  BatteryRig r(calParams());
  r.mon.setSoc(80.0);
  r.ina(14.0, 1.0);
  r.run(50.0, 1.0);
  r.ina(14.0, 10.0);  // above the tail current for one interval
  r.run(4.0, 1.0);
  r.ina(14.0, 1.0);
  r.run(50.0, 1.0);
  EXPECT_FALSE(r.mon.fullChargeDetected());
  EXPECT_LT(r.mon.socPercent(), 100.0);
  r.run(12.0, 1.0);
  EXPECT_TRUE(r.mon.fullChargeDetected());
}

TEST(FullCharge, NeedsChargedVoltage) {
  BatteryRig r(calParams());
  r.mon.setSoc(80.0);
  r.ina(13.7, 1.0);
  r.run(600.0, 1.0);
  EXPECT_FALSE(r.mon.fullChargeDetected());
  // Discharging at the tail magnitude counts too (|current|), as the specification says.
  r.ina(13.9, -3.0);
  r.run(64.0, 1.0);
  EXPECT_TRUE(r.mon.fullChargeDetected());
}

TEST(FullCharge, NotDeclaredOnStaleSensor) {
  BatteryRig r(calParams());
  r.mon.setSoc(80.0);
  r.ina(14.0, 30.0);
  r.tick(1.0);
  // The INA228 stops answering: stamps freeze, the monitor sees no current.
  for (int i = 0; i < 300; ++i) {
    r.now += fromSec(1.0);
    r.in.now = r.now;
    r.ev.clear();
    r.mon.updateBatterySoc(r.in, 0.0, r.ev);
  }
  EXPECT_FALSE(r.mon.fullChargeDetected());
  EXPECT_LT(r.mon.socPercent(), 100.0);
}

TEST(GainCorrection, AppliedWithRateLimit) {
  BatteryRig r(calParams());
  r.mon.setSoc(95.0);  // reference: the count is 190 Ah, nameplate 200 Ah
  ASSERT_GT(holdFull(r), 0.0);
  EXPECT_EQ(r.mon.lastGainGuard(), GainGuard::Applied);
  EXPECT_TRUE(r.sawEvent(EventCode::ShuntGainCorrected));
  // desired 200/190 = +5.3 %, limited to MAX_GAIN_ADJUSTMENT_PER_CYCLE.
  const double f = 1.0 + battery_k::MAX_GAIN_ADJUSTMENT_PER_CYCLE;
  EXPECT_NEAR(r.mon.ledger().DynamicShuntGainFactor, f, 1e-12);
  EXPECT_NEAR(r.mon.correctedBcur(10.0), 10.0 * f, 1e-12);
}

TEST(GainCorrection, LowersGainWhenCountRunsAhead) {
  BatteryRig r(calParams());
  r.mon.setSoc(90.0);
  r.ina(13.0, 20.0);  // 30 Ah into a bank with 20 Ah of room: count runs ahead
  r.run(1.5 * 3600.0, 1.0);
  ASSERT_GT(holdFull(r), 0.0);
  EXPECT_EQ(r.mon.lastGainGuard(), GainGuard::Applied);
  EXPECT_NEAR(r.mon.ledger().DynamicShuntGainFactor, 1.0 - battery_k::MAX_GAIN_ADJUSTMENT_PER_CYCLE, 1e-12);
}

TEST(GainCorrection, MinimumIntervalGuard) {
  BatteryRig r(calParams());
  r.mon.setSoc(95.0);
  ASSERT_GT(holdFull(r), 0.0);
  const double f1 = r.mon.ledger().DynamicShuntGainFactor;
  r.run(4.0, 1.0);  // still full: detection repeats, correction throttled
  EXPECT_EQ(r.mon.lastGainGuard(), GainGuard::TooSoon);
  r.mon.setSoc(95.0);
  r.ina(12.8, 0.0);
  r.run(3600.0, 10.0);
  ASSERT_GT(holdFull(r), 0.0);
  EXPECT_EQ(r.mon.lastGainGuard(), GainGuard::TooSoon);
  EXPECT_DOUBLE_EQ(r.mon.ledger().DynamicShuntGainFactor, f1);
  // After MIN_GAIN_CORRECTION_INTERVAL it may correct again.
  r.mon.setSoc(95.0);
  r.ina(12.8, 0.0);
  r.run(toSec(fromMs(battery_k::MIN_GAIN_CORRECTION_INTERVAL_MS)), 10.0);
  r.mon.setSoc(95.0);
  ASSERT_GT(holdFull(r), 0.0);
  EXPECT_EQ(r.mon.lastGainGuard(), GainGuard::Applied);
  EXPECT_GT(r.mon.ledger().DynamicShuntGainFactor, f1);
}

TEST(GainCorrection, FeatureOffGuard) {
  Params p = calParams();
  p.AutoShuntGainCorrection = false;
  BatteryRig r(p);
  r.mon.setSoc(95.0);
  ASSERT_GT(holdFull(r), 0.0);
  EXPECT_EQ(r.mon.lastGainGuard(), GainGuard::FeatureOff);
  EXPECT_DOUBLE_EQ(r.mon.ledger().DynamicShuntGainFactor, 1.0);
}

TEST(GainCorrection, NoReferenceGuard) {
  BatteryRig r(calParams());  // no setSoc / full charge yet: the count is a guess
  ASSERT_GT(holdFull(r), 0.0);
  EXPECT_EQ(r.mon.lastGainGuard(), GainGuard::NoReference);
  EXPECT_DOUBLE_EQ(r.mon.ledger().DynamicShuntGainFactor, 1.0);
}

TEST(GainCorrection, ImplausibleCapacityGuard) {
  Params p = calParams();
  p.BatteryCapacity_Ah = 8.0;  // < 10 Ah
  BatteryRig r(p);
  r.mon.setSoc(95.0);
  r.ina(14.0, 0.05);  // within 2 % of 8 Ah
  double took = -1.0;
  for (int i = 0; i < 200 && took < 0; ++i) {
    r.tick(1.0);
    if (r.sawEvent(EventCode::FullChargeDetected)) took = i;
  }
  ASSERT_GT(took, 0.0);
  EXPECT_EQ(r.mon.lastGainGuard(), GainGuard::ImplausibleCapacity);
  EXPECT_DOUBLE_EQ(r.mon.ledger().DynamicShuntGainFactor, 1.0);
}

TEST(GainCorrection, ErrorTooLargeGuard) {
  BatteryRig r(calParams());
  r.mon.setSoc(50.0);  // 100 Ah counted at "full": 50 % off, a fault, not calibration
  ASSERT_GT(holdFull(r), 0.0);
  EXPECT_EQ(r.mon.lastGainGuard(), GainGuard::ErrorTooLarge);
  EXPECT_DOUBLE_EQ(r.mon.ledger().DynamicShuntGainFactor, 1.0);
}

TEST(GainCorrection, AbsoluteBoundsAndReset) {
  BatteryRig r(calParams());
  BatteryLedger l = r.mon.ledger();
  l.DynamicShuntGainFactor = battery_k::MAX_DYNAMIC_GAIN_FACTOR - 0.005;
  r.mon.restoreLedger(l);
  r.mon.setSoc(95.0);
  ASSERT_GT(holdFull(r), 0.0);
  EXPECT_EQ(r.mon.lastGainGuard(), GainGuard::Applied);
  EXPECT_DOUBLE_EQ(r.mon.ledger().DynamicShuntGainFactor, battery_k::MAX_DYNAMIC_GAIN_FACTOR);
  r.mon.resetSocGain();
  EXPECT_DOUBLE_EQ(r.mon.ledger().DynamicShuntGainFactor, 1.0);
}

// ---------------------------------------------------------------- auto-zero

Params zeroParams() {
  Params p = calParams();
  p.AutoAltCurrentZero = true;
  p.TempSource = 0;
  return p;
}

void engine(BatteryRig& r, double rpm, double tempF) {
  r.in.rpm = Reading{rpm, r.now, true};
  r.in.AlternatorTemperatureF = Reading{tempF, r.now, true};
}

TEST(AutoZero, HourlySequenceTimingAndOffset) {
  BatteryRig r(zeroParams());
  engine(r, 1500.0, 120.0);
  r.ina(13.5, 10.0);
  r.tick(1.0, 40.0);  // first tick starts the hourly timer
  r.run(3598.0, 1.0, 40.0);
  EXPECT_FALSE(r.mon.autoZeroActive());
  r.tick(1.0, 40.0);  // 3599 s after the first tick
  EXPECT_FALSE(r.mon.autoZeroActive());
  r.tick(1.0, 40.0);  // 3600 s
  ASSERT_TRUE(r.mon.autoZeroActive());
  EXPECT_TRUE(r.sawEvent(EventCode::AutoZeroStarted));
  EXPECT_TRUE(r.telem().autoZeroActive);
  // Field off: the Hall reading decays during the 2 s settle (30 A, ignored)
  // and then reads its true zero, 1.5 A.
  const TimeNs start = r.now;
  int activeTicks = 1;
  while (r.mon.autoZeroActive()) {
    const double elapsed = toSec(r.now + fromMs(100) - start);
    r.tick(0.1, elapsed <= 2.0 ? 30.0 : 1.5);
    if (r.mon.autoZeroActive()) ++activeTicks;
    ASSERT_LT(activeTicks, 1000);
  }
  EXPECT_EQ(activeTicks, battery_k::AUTO_ZERO_DURATION_MS / 100);
  EXPECT_TRUE(r.sawEvent(EventCode::AutoZeroDone));
  EXPECT_NEAR(r.mon.ledger().DynamicAltCurrentZero, 1.5, 1e-9);
  EXPECT_NEAR(r.mon.correctedAltAmps(41.5), 40.0, 1e-9);
  // Not again until the next hour.
  r.run(3500.0, 1.0, 40.0);
  EXPECT_FALSE(r.mon.autoZeroActive());
  r.mon.resetAltZero();
  EXPECT_DOUBLE_EQ(r.mon.ledger().DynamicAltCurrentZero, 0.0);
}

TEST(AutoZero, TemperatureShiftTriggers) {
  BatteryRig r(zeroParams());
  engine(r, 1500.0, 100.0);
  r.ina(13.5, 10.0);
  r.run(10.0, 1.0, 40.0);
  EXPECT_FALSE(r.mon.autoZeroActive());
  engine(r, 1500.0, 119.5);  // 19.5 degF: not yet
  r.run(10.0, 1.0, 40.0);
  EXPECT_FALSE(r.mon.autoZeroActive());
  engine(r, 1500.0, 120.0);  // 20 degF shift
  r.tick(1.0, 40.0);
  EXPECT_TRUE(r.mon.autoZeroActive());
}

TEST(AutoZero, NeedsEngineRunningAndFeatureOn) {
  BatteryRig r(zeroParams());
  engine(r, 150.0, 100.0);  // RPM < 200
  r.run(2.0 * 3600.0, 5.0);
  EXPECT_FALSE(r.mon.autoZeroActive());
  engine(r, 250.0, 100.0);
  r.tick(1.0);
  EXPECT_TRUE(r.mon.autoZeroActive());

  Params off = zeroParams();
  off.AutoAltCurrentZero = false;
  BatteryRig r2(off);
  engine(r2, 1500.0, 100.0);
  r2.run(2.0 * 3600.0, 5.0);
  engine(r2, 1500.0, 160.0);
  r2.run(10.0, 1.0);
  EXPECT_FALSE(r2.mon.autoZeroActive());
}

TEST(AutoZero, ImplausibleOffsetKeepsOldZero) {
  BatteryRig r(zeroParams());
  engine(r, 1500.0, 100.0);
  r.run(3605.0, 5.0, 40.0);  // first tick starts the timer, 3600 s later it fires
  ASSERT_TRUE(r.mon.autoZeroActive());
  r.run(12.0, 0.1, 25.0);  // current still flowing: not a zero
  EXPECT_FALSE(r.mon.autoZeroActive());
  EXPECT_DOUBLE_EQ(r.mon.ledger().DynamicAltCurrentZero, 0.0);
}

TEST(AutoZero, NoFreshSamplesKeepsOldZero) {
  BatteryRig r(zeroParams());
  engine(r, 1500.0, 100.0);
  r.run(3605.0, 5.0, 40.0);  // first tick starts the timer, 3600 s later it fires
  ASSERT_TRUE(r.mon.autoZeroActive());
  bool done = false;
  for (int i = 0; i < 200 && !done; ++i) {
    r.now += fromMs(100);
    r.in.now = r.now;
    r.in.altCurrentRaw.fresh = false;  // ADS1115 stopped converting
    r.ev.clear();
    r.mon.checkAutoZeroTriggers(r.in, r.ev);
    const bool active = r.mon.processAutoZero(r.in, r.ev);
    if (!active) {
      done = true;
      ASSERT_TRUE(r.sawEvent(EventCode::AutoZeroDone));
      for (std::size_t k = 0; k < r.ev.count; ++k)
        if (r.ev.items[k].code == EventCode::AutoZeroDone) {
          EXPECT_EQ(r.ev.items[k].detail, 1);
        }
    }
  }
  EXPECT_TRUE(done);
  EXPECT_DOUBLE_EQ(r.mon.ledger().DynamicAltCurrentZero, 0.0);
}

}  // namespace
}  // namespace xr
