// SoC, Peukert, energy, averages, predictions and current source
// (docs/batteries.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "battery_fixture.h"
#include "params/constants.h"

namespace xr {
namespace {

using test::BatteryRig;

Params baseParams() {
  Params p;
  p.BatteryCapacity_Ah = 200.0;
  p.ChargeEfficiency = 100.0;
  p.PeukertExponent = 1.0;  // factor 1: the count equals the current integral
  p.SOCUpdateInterval = 2000;
  p.ChargedVoltage = 13.8;
  p.ChargedDetectionTime = 60.0;
  p.TailCurrent = 2.0;
  p.CurrentThreshold = 1.0;
  return p;
}

TEST(BatterySoc, CoulombCountMatchesAnalyticIntegralOverADay) {
  Params p = baseParams();
  p.BatteryCapacity_Ah = 10000.0;  // no clamping during the day
  BatteryRig r(p);
  ASSERT_TRUE(r.mon.setSoc(50.0));
  const double start = r.mon.ledger().CoulombCount_Ah;
  // I(t) = 3 + 15 sin(2 pi t / 5 h): charging and discharging, 4.8 periods.
  const double T = 5.0 * 3600.0, day = 86400.0, dt = 1.0;
  auto I = [&](double t) { return 3.0 + 15.0 * std::sin(2.0 * std::numbers::pi * t / T); };
  for (double t = 0.0; t < day; t += dt) {
    r.ina(12.8, I(t + dt / 2.0));  // sample at the middle of the tick
    r.tick(dt);
  }
  r.run(2.0, 1.0);  // flush the last SoC interval with zero current
  r.ina(12.8, 0.0);
  r.run(4.0, 1.0);
  const double expected = 3.0 * 24.0 + 15.0 * (T / 3600.0) / (2.0 * std::numbers::pi) *
                                           (1.0 - std::cos(2.0 * std::numbers::pi * day / T));
  const BatteryLedger l = r.mon.ledger();
  const double counted = l.CoulombCount_Ah + l.coulombAccumulator_Ah - start;
  EXPECT_NEAR(counted, expected, 0.001 * std::fabs(expected));
  // The committed count alone (0.01 Ah steps) is within one step of it.
  EXPECT_NEAR(l.CoulombCount_Ah - start, expected, 0.001 * std::fabs(expected) + 0.01);
}

TEST(BatterySoc, ChargeEfficiencyAppliesOnChargingBranchOnly) {
  Params p = baseParams();
  p.ChargeEfficiency = 95.0;
  BatteryRig r(p);
  r.mon.setSoc(50.0);
  r.ina(13.0, 10.0);
  r.run(3600.0, 0.5);
  EXPECT_NEAR(r.mon.ledger().CoulombCount_Ah, 100.0 + 9.5, 0.02);
  r.ina(12.5, -10.0);
  r.run(3600.0, 0.5);
  // Discharge is not scaled by the efficiency (Peukert exponent 1).
  EXPECT_NEAR(r.mon.ledger().CoulombCount_Ah, 99.5, 0.02);
}

TEST(BatterySoc, SocClampedToCapacityAndZero) {
  BatteryRig r(baseParams());
  r.mon.setSoc(99.0);
  r.ina(13.0, 50.0);
  r.run(3600.0, 1.0);
  EXPECT_DOUBLE_EQ(r.mon.socPercent(), 100.0);
  r.ina(12.0, -100.0);
  r.run(3 * 3600.0, 1.0);
  EXPECT_DOUBLE_EQ(r.mon.socPercent(), 0.0);
}

TEST(BatteryPeukert, FactorAtKnownRatios) {
  // (I20 / I)^(n-1)
  EXPECT_NEAR(BatteryMonitor::peukertFactor(20.0, 200.0, 10.0, 1.2), std::pow(0.5, 0.2), 1e-12);
  EXPECT_NEAR(BatteryMonitor::peukertFactor(5.0, 200.0, 10.0, 1.25), std::pow(2.0, 0.25), 1e-12);
  EXPECT_DOUBLE_EQ(BatteryMonitor::peukertFactor(10.0, 200.0, 10.0, 1.2), 1.0);
}

TEST(BatteryPeukert, OnlyAboveCOver100) {
  // C/100 of 200 Ah is 2 A: at or below it the nameplate applies.
  EXPECT_DOUBLE_EQ(BatteryMonitor::peukertFactor(2.0, 200.0, 10.0, 1.3), 1.0);
  EXPECT_DOUBLE_EQ(BatteryMonitor::peukertFactor(1.0, 200.0, 10.0, 1.3), 1.0);
  EXPECT_NE(BatteryMonitor::peukertFactor(2.1, 200.0, 10.0, 1.3), 1.0);
}

TEST(BatteryPeukert, Clamps) {
  // (1/1000)^0.6 = 0.016 -> 0.5 ; (1000/1.5)^0.6 = 49 -> 2.0
  EXPECT_DOUBLE_EQ(BatteryMonitor::peukertFactor(1000.0, 100.0, 1.0, 1.6), 0.5);
  EXPECT_DOUBLE_EQ(BatteryMonitor::peukertFactor(1.5, 100.0, 1000.0, 1.6), 2.0);
  // Junk rated current never produces a factor outside the clamp or NaN.
  EXPECT_DOUBLE_EQ(BatteryMonitor::peukertFactor(10.0, 100.0, 0.0, 1.6), 1.0);
}

TEST(BatteryPeukert, HighDischargeDepletesFaster) {
  Params p = baseParams();
  p.PeukertExponent = 1.2;
  p.PeukertRatedCurrent_A = 10.0;
  BatteryRig r(p);
  r.mon.setSoc(100.0);
  r.ina(12.4, -20.0);
  r.run(3600.0, 0.5);
  const double removed = 200.0 - r.mon.ledger().CoulombCount_Ah;
  EXPECT_NEAR(removed, 20.0 / std::pow(0.5, 0.2), 0.02);  // 22.97 Ah, not 20
}

TEST(BatteryEnergy, FiftyMilliwattsForADayIsOnePointTwoWh) {
  Params p = baseParams();
  BatteryRig r(p);
  BatteryLedger big = r.mon.ledger();
  big.DischargedEnergy_AllTime_Wh = 1.0e9;  // a huge lifetime must not swallow it
  big.SolarChargedEnergy_AllTime_Wh = 1.0e9;
  r.mon.restoreLedger(big);
  r.ina(12.5, -0.004);  // 50 mW out of the battery
  r.in.solarPowerW = Reading{0.05, r.now, true};
  const double dt = 0.0025;  // the 400 Hz control tick for the first hour
  for (int i = 0; i < 3600 * 400; ++i) {
    r.in.solarPowerW.stamp = r.now + fromSec(dt);
    r.tick(dt);
  }
  for (int i = 0; i < 23 * 3600 * 10; ++i) {
    r.in.solarPowerW.stamp = r.now + fromSec(0.1);
    r.tick(0.1);
  }
  const BatteryTelemetry t = r.telem();
  EXPECT_NEAR(t.DischargedEnergy_Wh, 1.2, 0.012);
  EXPECT_NEAR(t.SolarChargedEnergy_Wh, 1.2, 0.012);
  EXPECT_NEAR(r.mon.ledger().DischargedEnergy_AllTime_Wh - 1.0e9, 1.2, 0.012);
  EXPECT_NEAR(r.mon.ledger().SolarChargedEnergy_AllTime_Wh - 1.0e9, 1.2, 0.012);
  EXPECT_DOUBLE_EQ(t.ChargedEnergy_Wh, 0.0);
}

TEST(BatteryEnergy, AlternatorEnergyOnTimeAndFuel) {
  BatteryRig r(baseParams());
  r.ina(13.5, 40.0);
  // Battery takes 40 A at 13.5 V; the alternator makes 80 A for 1 h = 1080 Wh.
  r.run(3600.0, 0.5, 80.0);
  r.run(2.0, 1.0, 0.5);  // below CurrentThreshold: alternator off
  const BatteryTelemetry t = r.telem();
  EXPECT_NEAR(t.AlternatorChargedEnergy_Wh, 1080.0, 0.5);
  EXPECT_NEAR(t.AlternatorOnTime_s, 3600.0, 1.0);
  // 1080 Wh * 3600 / 0.15 / 36000 J/mL = 720 mL, rolled in hundredths of a litre.
  EXPECT_NEAR(t.AlternatorFuelUsed_L, 0.72, 0.0101);
  EXPECT_LE(t.AlternatorFuelUsed_L, 0.72 + 1e-9);
  EXPECT_NEAR(t.ChargedEnergy_Wh, 13.5 * 40.0, 0.5);
  EXPECT_NEAR(t.AlternatorChargedEnergy_AllTime_Wh, t.AlternatorChargedEnergy_Wh, 1e-6);
}

TEST(BatteryEnergy, ChargeCyclesUseDetectedSystemClass) {
  BatteryRig r(baseParams());
  r.mon.setSoc(0.0);
  r.ina(12.0, 50.0);
  r.run(4.0 * 3600.0, 1.0);  // 2400 Wh into a 200 Ah x 12 V = 2400 Wh bank
  BatteryTelemetry t = r.telem();
  EXPECT_EQ(t.nominalVoltage, 12);
  EXPECT_NEAR(t.ChargeCycles, 1.0, 0.002);
  EXPECT_NEAR(t.ChargeCycles_AllTime, 1.0, 0.002);

  BatteryRig r24(baseParams());
  r24.mon.setSoc(0.0);
  r24.ina(24.0, 25.0);
  r24.run(4.0 * 3600.0, 1.0);  // 2400 Wh into a 4800 Wh bank
  t = r24.telem();
  EXPECT_EQ(t.nominalVoltage, 24);
  EXPECT_NEAR(t.ChargeCycles, 0.5, 0.001);
}

TEST(BatteryAverages, TimeWeightedSocAndVoltage) {
  BatteryRig r(baseParams());
  r.mon.setSoc(40.0);
  r.ina(12.0, 0.0);
  r.run(1000.0, 1.0);
  r.mon.setSoc(80.0);
  r.ina(13.6, 0.0);  // below ChargedVoltage: no full-charge reset
  r.run(3000.0, 1.0);
  const BatteryTelemetry t = r.telem();
  EXPECT_NEAR(t.AvgSOC, (40.0 * 1000 + 80.0 * 3000) / 4000.0, 0.05);
  EXPECT_NEAR(t.AvgSOC_AllTime, t.AvgSOC, 1e-9);
  EXPECT_NEAR(t.AvgVoltage_AllTime, (12.0 * 1000 + 13.6 * 3000) / 4000.0, 0.005);

  // Lifetime numerators and denominators survive a restart; session ones do not.
  BatteryRig r2(baseParams());
  r2.mon.restoreLedger(r.mon.ledger());
  r2.mon.setSoc(0.0);
  r2.ina(12.0, 0.0);
  r2.run(4000.0, 1.0);
  const BatteryTelemetry t2 = r2.telem();
  EXPECT_NEAR(t2.AvgSOC, 0.0, 1e-9);
  EXPECT_NEAR(t2.AvgSOC_AllTime, t.AvgSOC / 2.0, 0.05);
}

TEST(BatteryPredictions, ChargeAndDischargeTimesWithSentinels) {
  BatteryRig r(baseParams());
  r.mon.setSoc(50.0);
  r.ina(13.5, 20.0);
  r.tick(0.1);  // the first call only starts the clocks
  BatteryTelemetry t0 = r.telem();
  EXPECT_DOUBLE_EQ(t0.timeToFullChargeMin, k::PREDICTION_NA);
  r.tick(1.2);  // first calculateChargeTimes after INA_SLOW_INTERVAL_MS
  BatteryTelemetry t = r.telem();
  EXPECT_NEAR(t.timeToFullChargeMin, 100.0 / 20.0 * 60.0, 0.5);
  EXPECT_DOUBLE_EQ(t.timeToFullDischargeMin, k::PREDICTION_NA);

  r.ina(12.5, -10.0);
  r.tick(1.2);
  t = r.telem();
  EXPECT_NEAR(t.timeToFullDischargeMin, r.mon.socPercent() * 2.0 / 10.0 * 60.0, 0.5);
  EXPECT_DOUBLE_EQ(t.timeToFullChargeMin, k::PREDICTION_NA);

  r.ina(12.5, 0.005);
  r.tick(1.2);
  t = r.telem();
  EXPECT_DOUBLE_EQ(t.timeToFullChargeMin, k::PREDICTION_NA);
  EXPECT_DOUBLE_EQ(t.timeToFullDischargeMin, k::PREDICTION_NA);
}

TEST(BatterySource, VoltageIsAlwaysIbv) {
  BatteryRig r(baseParams());
  r.in.IBV = Reading{13.1, r.now, true};
  r.in.BatteryV = Reading{12.0, r.now, true};
  r.in.VictronVoltage = Reading{12.5, r.now, true};
  EXPECT_DOUBLE_EQ(r.mon.getBatteryVoltage(r.in), 13.1);
}

TEST(BatterySource, VictronCurrentWhenSelectedAndFreshElseIna) {
  Params p = baseParams();
  p.BatteryCurrentSource = 3;
  BatteryRig r(p);
  r.in.now = r.now;
  r.in.Bcur = Reading{5.0, r.now, true};
  r.in.VictronCurrent = Reading{7.0, r.now - fromMs(k::VICTRON_STALE_MS), false};
  EXPECT_DOUBLE_EQ(r.mon.getBatteryCurrent(r.in), 7.0);  // exactly 10 s old: still fresh
  r.in.VictronCurrent.stamp = r.now - fromMs(k::VICTRON_STALE_MS) - fromMs(1);
  EXPECT_DOUBLE_EQ(r.mon.getBatteryCurrent(r.in), 5.0);  // stale > 10 s: INA228
  r.in.VictronCurrent = Reading{};                       // never received
  EXPECT_DOUBLE_EQ(r.mon.getBatteryCurrent(r.in), 5.0);

  Params p0 = baseParams();
  p0.BatteryCurrentSource = 0;
  BatteryRig r0(p0);
  r0.in.now = r0.now;
  r0.in.Bcur = Reading{5.0, r0.now, true};
  r0.in.VictronCurrent = Reading{7.0, r0.now, true};
  EXPECT_DOUBLE_EQ(r0.mon.getBatteryCurrent(r0.in), 5.0);
}

TEST(BatterySource, SocFollowsSelectedSourceAndFallsBack) {
  Params p = baseParams();
  p.BatteryCurrentSource = 3;
  BatteryRig r(p);
  r.mon.setSoc(50.0);
  r.ina(13.0, 20.0);  // INA says 20 A
  for (int i = 0; i < 3600; ++i) {
    r.in.VictronCurrent = Reading{10.0, r.now + fromSec(1.0), true};  // VE.Direct says 10 A
    r.tick(1.0);
  }
  EXPECT_NEAR(r.mon.ledger().CoulombCount_Ah, 110.0, 0.02);
  EXPECT_TRUE(r.telem().usingVictronCurrent);
  // VE.Direct goes silent: after 10 s the INA228 takes over.
  r.run(3600.0, 1.0);
  EXPECT_FALSE(r.telem().usingVictronCurrent);
  EXPECT_NEAR(r.mon.ledger().CoulombCount_Ah, 110.0 + 10.0 * 10.0 / 3600.0 + 20.0 * 3590.0 / 3600.0, 0.05);
}

TEST(BatterySource, StaleInaIsNotIntegrated) {
  BatteryRig r(baseParams());
  r.mon.setSoc(50.0);
  r.in.IBV = Reading{13.0, r.now, true};
  r.in.Bcur = Reading{50.0, r.now, true};
  // Samples never refreshed (stamp frozen): counted for 2 s at most.
  for (int i = 0; i < 600; ++i) {
    r.now += fromSec(1.0);
    r.in.now = r.now;
    r.ev.clear();
    r.mon.updateBatterySoc(r.in, 0.0, r.ev);
  }
  EXPECT_LT(r.mon.ledger().CoulombCount_Ah, 100.0 + 50.0 * 3.0 / 3600.0);
}

TEST(BatteryLedgerTest, RoundTripAndSanitising) {
  BatteryRig r(baseParams());
  r.mon.setSoc(30.0);
  r.ina(13.0, 12.3);
  r.run(5000.0, 1.0, 20.0);
  const BatteryLedger l = r.mon.ledger();
  BatteryMonitor m2(baseParams());
  m2.restoreLedger(l);
  EXPECT_EQ(m2.ledger(), l);
  EXPECT_GT(l.ChargedEnergy_AllTime_Wh, 0.0);

  BatteryLedger bad = l;
  bad.CoulombCount_Ah = std::nan("");
  bad.DynamicShuntGainFactor = 7.0;
  bad.ChargedEnergy_AllTime_Wh = -5.0;
  bad.DynamicAltCurrentZero = std::nan("");
  BatteryMonitor m3(baseParams());
  m3.restoreLedger(bad);
  const BatteryLedger s = m3.ledger();
  EXPECT_DOUBLE_EQ(s.CoulombCount_Ah, 200.0 * kUnknownSocPercent / 100.0);  // NaN: unknown
  EXPECT_LE(s.DynamicShuntGainFactor, battery_k::MAX_DYNAMIC_GAIN_FACTOR);
  EXPECT_DOUBLE_EQ(s.ChargedEnergy_AllTime_Wh, 0.0);
  EXPECT_DOUBLE_EQ(s.DynamicAltCurrentZero, 0.0);
}

TEST(BatteryCommands, FreshMonitorGuessesFullUntilKnown) {
  BatteryRig r(baseParams());
  EXPECT_DOUBLE_EQ(r.mon.socPercent(), kUnknownSocPercent);
  EXPECT_FALSE(r.mon.socKnown());
  r.mon.setSoc(60.0);
  EXPECT_TRUE(r.mon.socKnown());
  BatteryRig restored(baseParams());
  restored.mon.restoreLedger(r.mon.ledger());
  EXPECT_TRUE(restored.mon.socKnown());
  BatteryRig detected(baseParams());
  detected.ina(14.0, 1.0);
  detected.run(70.0, 1.0);
  EXPECT_TRUE(detected.mon.fullChargeDetected());
  EXPECT_TRUE(detected.mon.socKnown());
}

TEST(BatteryCommands, SetSocRejectsOutOfRange) {
  BatteryRig r(baseParams());
  ASSERT_TRUE(r.mon.setSoc(25.0));
  EXPECT_FALSE(r.mon.setSoc(-1.0));
  EXPECT_FALSE(r.mon.setSoc(100.5));
  EXPECT_FALSE(r.mon.setSoc(std::nan("")));
  EXPECT_DOUBLE_EQ(r.mon.socPercent(), 25.0);
}

}  // namespace
}  // namespace xr
