// SocCounter on its own (docs/batteries.md "State of charge", "Full-charge
// detection"): the 0.01 Ah commit step, efficiency and Peukert, the
// full-charge timer at its threshold and just below, the reset, restore.
#include "battery/soc_counter.h"

#include <gtest/gtest.h>

#include <cmath>

#include "params/constants.h"
#include "params/derived.h"

namespace xr {
namespace {

Params bank() {
  Params p;
  p.BatteryCapacity_Ah = 200.0;
  p.ChargeEfficiency = 90.0;
  p.PeukertExponent = 1.0;
  p.ChargedDetectionTime = 60.0;
  p.TailCurrent = 2.0;  // % of C: 4 A
  return p;
}

TEST(SocCounter, AFreshCountGuessesFullAndSaysItIsUnknown) {
  SocCounter s(200.0);
  EXPECT_DOUBLE_EQ(s.percent(200.0), kUnknownSocPercent);
  EXPECT_EQ(s.source(), SocSource::Unknown);
}

TEST(SocCounter, CommitsWholeHundredthsAndKeepsTheRest) {
  const Params p = bank();
  SocCounter s(200.0);
  s.setByOperator(50.0, 200.0);
  s.integrate(-0.009, 3600.0);  // 0.009 Ah out: below one step
  s.commit(3600.0, p);
  EXPECT_DOUBLE_EQ(s.countAh(), 100.0);
  s.integrate(-0.002, 3600.0);  // the remainder passes 0.01 Ah: one step committed, 0.001 kept
  s.commit(3600.0, p);
  EXPECT_NEAR(s.countAh(), 99.99, 1e-12);
  BatteryLedger l;
  s.toLedger(l);
  EXPECT_NEAR(l.coulombAccumulator_Ah, -0.001, 1e-12);
}

TEST(SocCounter, EfficiencyOnChargeOnly) {
  const Params p = bank();
  SocCounter s(200.0);
  s.setByOperator(50.0, 200.0);
  s.integrate(10.0, 3600.0);
  EXPECT_DOUBLE_EQ(s.commit(3600.0, p), 9.0);
  s.integrate(-10.0, 3600.0);
  EXPECT_DOUBLE_EQ(s.commit(3600.0, p), -10.0);
  EXPECT_NEAR(s.countAh(), 99.0, 1e-9);
  EXPECT_NEAR(s.sinceReferenceAh(), 99.0, 1e-9);
}

TEST(SocCounter, ACountIsClampedToTheBank) {
  const Params p = bank();
  SocCounter s(200.0);
  s.integrate(100.0, 3600.0);
  s.commit(3600.0, p);
  EXPECT_DOUBLE_EQ(s.countAh(), 200.0);
}

FullChargeInput fullAt(double elapsed, double amps, double volts) {
  FullChargeInput f;
  f.elapsed_s = elapsed;
  f.live = true;
  f.amps = amps;
  f.volts = volts;
  return f;
}

TEST(SocCounter, FullAfterChargedDetectionTimeNotBefore) {
  const Params p = bank();
  const double v = chargedVoltageV(p);
  SocCounter s(200.0);
  for (int i = 0; i < 29; ++i) EXPECT_FALSE(s.fullChargeDue(fullAt(2.0, 4.0, v), p)) << i;  // 58 s
  EXPECT_TRUE(s.fullChargeDue(fullAt(2.0, 4.0, v), p));                                     // 60 s
  s.markFull(200.0);
  EXPECT_TRUE(s.fullDetected());
  EXPECT_EQ(s.source(), SocSource::Counted);
  EXPECT_DOUBLE_EQ(s.percent(200.0), 100.0);
  // The tail lapses: the detector resets.
  EXPECT_FALSE(s.fullChargeDue(fullAt(2.0, 4.01, v), p));
  EXPECT_FALSE(s.fullDetected());
}

TEST(SocCounter, NoFullChargeOnADeadSensorOrBelowTheVoltage) {
  const Params p = bank();
  SocCounter s(200.0);
  FullChargeInput dead = fullAt(120.0, 0.0, chargedVoltageV(p));
  dead.live = false;
  EXPECT_FALSE(s.fullChargeDue(dead, p));
  EXPECT_FALSE(s.fullChargeDue(fullAt(120.0, 0.0, chargedVoltageV(p) - 0.01), p));
}

TEST(SocCounter, PredictsTimeToFullAndToEmpty) {
  SocCounter s(200.0);
  s.setByOperator(50.0, 200.0);
  s.predict(20.0, 200.0);
  EXPECT_DOUBLE_EQ(s.timeToFullMin(), 300.0);
  EXPECT_DOUBLE_EQ(s.timeToEmptyMin(), k::PREDICTION_NA);
  s.predict(-10.0, 200.0);
  EXPECT_DOUBLE_EQ(s.timeToEmptyMin(), 600.0);
  s.predict(0.005, 200.0);  // within +-0.01 A: neither
  EXPECT_DOUBLE_EQ(s.timeToFullMin(), k::PREDICTION_NA);
  EXPECT_DOUBLE_EQ(s.timeToEmptyMin(), k::PREDICTION_NA);
}

TEST(SocCounter, RestoreKeepsAValidSourceAndRefusesADamagedOne) {
  BatteryLedger l;
  l.valid = true;
  l.CoulombCount_Ah = 120.0;
  l.SocSource = 1.0;
  SocCounter s(200.0);
  s.restore(l, 200.0);
  EXPECT_DOUBLE_EQ(s.countAh(), 120.0);
  EXPECT_EQ(s.source(), SocSource::OcvEstimate);
  EXPECT_FALSE(s.referenceValid()) << "a restored count is no reference for the gain";
  l.SocSource = 7.0;
  s.restore(l, 200.0);
  EXPECT_EQ(s.source(), SocSource::Unknown);
  l.CoulombCount_Ah = std::nan("");
  l.SocSource = 2.0;
  s.restore(l, 200.0);
  EXPECT_DOUBLE_EQ(s.countAh(), 200.0 * kUnknownSocPercent / 100.0);
  EXPECT_EQ(s.source(), SocSource::Unknown);
}

}  // namespace
}  // namespace xr
