// AlternatorWear against hand-computed cases (docs/operations.md "Alternator wear").
#include "health/alternator_wear.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xr {
namespace {

Params params(int insulationClass) {
  Params p;
  p.AltInsulationClass = insulationClass;
  p.AltWindingRiseF = 120.0;
  p.AltRatedCurrent_A = 100.0;
  return p;
}

// degF of a degC.
double f(double c) { return c * 9.0 / 5.0 + 32.0; }

TEST(AlternatorWear, OneHourAtTheClassTemperatureUsesOneTwentyThousandth) {
  // Class F = 155 degC; no current, so the windings are at the sensor's
  // temperature: 1 h / 20 000 h = 0.005 %.
  AlternatorWear w;
  w.update(3600.0, true, f(155.0), 0.0, params(1));
  EXPECT_NEAR(w.ledger().LifeUsed_pct, 0.005, 1e-12);
  EXPECT_NEAR(w.ledger().RunTime_s, 3600.0, 1e-9);
}

TEST(AlternatorWear, TenDegreesHotterHalvesTheLifeTenCoolerDoublesIt) {
  AlternatorWear hot, cool;
  hot.update(3600.0, true, f(165.0), 0.0, params(1));
  cool.update(3600.0, true, f(145.0), 0.0, params(1));
  EXPECT_NEAR(hot.ledger().LifeUsed_pct, 0.010, 1e-12);
  EXPECT_NEAR(cool.ledger().LifeUsed_pct, 0.0025, 1e-12);
}

TEST(AlternatorWear, EachInsulationClassHasItsOwnTemperature) {
  // 130 degC for 1 h: class B at its rating (0.005 %), class H 50 degC
  // under its 180 (2^-5 of that), class F 25 under (2^-2.5).
  AlternatorWear b, fc, h;
  b.update(3600.0, true, f(130.0), 0.0, params(0));
  fc.update(3600.0, true, f(130.0), 0.0, params(1));
  h.update(3600.0, true, f(130.0), 0.0, params(2));
  EXPECT_NEAR(b.ledger().LifeUsed_pct, 0.005, 1e-12);
  EXPECT_NEAR(fc.ledger().LifeUsed_pct, 0.005 * std::pow(2.0, -2.5), 1e-12);
  EXPECT_NEAR(h.ledger().LifeUsed_pct, 0.005 / 32.0, 1e-12);
}

TEST(AlternatorWear, TheWindingsRiseWithTheSquareOfTheCurrent) {
  // At the rated 100 A the windings run AltWindingRiseF = 120 degF above the
  // sensor; at 50 A a quarter of it, 30 degF.
  const Params p = params(1);
  EXPECT_NEAR(AlternatorWear::windingC(200.0, 100.0, p), (320.0 - 32.0) * 5.0 / 9.0, 1e-9);
  EXPECT_NEAR(AlternatorWear::windingC(200.0, 50.0, p), (230.0 - 32.0) * 5.0 / 9.0, 1e-9);
  EXPECT_NEAR(AlternatorWear::windingC(200.0, -5.0, p), (200.0 - 32.0) * 5.0 / 9.0, 1e-9);
  // Sensor 191 degF (88.3 degC) at 100 A: windings 311 degF = 155 degC, class F's rating.
  AlternatorWear w;
  w.update(1800.0, true, 191.0, 100.0, p);
  EXPECT_NEAR(w.ledger().LifeUsed_pct, 0.0025, 1e-9);
}

TEST(AlternatorWear, BandsCountFromTheirEdgeUp) {
  const Params p = params(1);
  AlternatorWear w;
  w.update(60.0, true, 149.9, 0.0, p);  // under every band
  w.update(60.0, true, 150.0, 0.0, p);  // the first band's edge counts
  w.update(60.0, true, 199.9, 0.0, p);  // 150 and 175
  w.update(60.0, true, 200.0, 0.0, p);  // 150, 175, 200
  w.update(60.0, true, 225.0, 0.0, p);  // all four
  const auto& t = w.ledger().TimeAbove_s;
  EXPECT_DOUBLE_EQ(t[0], 240.0);
  EXPECT_DOUBLE_EQ(t[1], 180.0);
  EXPECT_DOUBLE_EQ(t[2], 120.0);
  EXPECT_DOUBLE_EQ(t[3], 60.0);
  EXPECT_DOUBLE_EQ(w.ledger().RunTime_s, 300.0);
}

TEST(AlternatorWear, HeatSoakCountsButNotAsRunningAndUnknownTemperatureCountsNothing) {
  const Params p = params(1);
  AlternatorWear w;
  w.update(600.0, false, 210.0, 0.0, p);  // stopped, hot
  EXPECT_DOUBLE_EQ(w.ledger().RunTime_s, 0.0);
  EXPECT_DOUBLE_EQ(w.ledger().TimeAbove_s[2], 600.0);
  EXPECT_GT(w.ledger().LifeUsed_pct, 0.0);
  const double life = w.ledger().LifeUsed_pct;
  w.update(600.0, true, std::nan(""), 0.0, p);  // no sensor
  EXPECT_DOUBLE_EQ(w.ledger().RunTime_s, 600.0);
  EXPECT_DOUBLE_EQ(w.ledger().TimeAbove_s[0], 600.0);
  EXPECT_DOUBLE_EQ(w.ledger().LifeUsed_pct, life);
}

TEST(AlternatorWear, ADamagedSavedLedgerStartsAfreshFieldByField) {
  AlternatorWearLedger l;
  l.RunTime_s = 7200.0;
  l.TimeAbove_s = {100.0, std::nan(""), -5.0, 1.0};
  l.LifeUsed_pct = std::nan("");
  l.BeltSlipEvents = 2.0;
  AlternatorWear w;
  w.restore(l);
  EXPECT_DOUBLE_EQ(w.ledger().RunTime_s, 7200.0);
  EXPECT_DOUBLE_EQ(w.ledger().TimeAbove_s[0], 100.0);
  EXPECT_DOUBLE_EQ(w.ledger().TimeAbove_s[1], 0.0);
  EXPECT_DOUBLE_EQ(w.ledger().TimeAbove_s[2], 0.0);
  EXPECT_DOUBLE_EQ(w.ledger().LifeUsed_pct, 0.0);
  EXPECT_DOUBLE_EQ(w.ledger().BeltSlipEvents, 2.0);
}

}  // namespace
}  // namespace xr
