// ResistanceEstimator on synthetic steps (docs/batteries.md "Internal resistance").
#include "battery/resistance_estimator.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xr {
namespace {

using namespace resistance_k;

// Feeds `seconds` of a constant current at 10 Hz to a bank of EMF e and series R (ohm).
int feed(ResistanceEstimator& r, double seconds, double amps, double e, double ohm, double tempC = 25.0,
         double capacityAh = 200.0) {
  int taken = 0;
  for (int i = 0; i < static_cast<int>(seconds * 10); ++i)
    taken += r.update(0.1, amps, e + amps * ohm, tempC, capacityAh);
  return taken;
}

TEST(ResistanceEstimator, AStepBetweenTwoHoldsIsOneSample) {
  ResistanceEstimator r;
  // Long enough without charge first (kAfterChargeS + the window).
  EXPECT_EQ(feed(r, kAfterChargeS + kWindowS, -1.0, 12.6, 0.004), 0);
  EXPECT_EQ(feed(r, kAfterS + 5, -11.0, 12.6, 0.004), 1);
  EXPECT_EQ(r.samples(), 1);
  EXPECT_TRUE(std::isnan(r.medianMohm()));  // one is not enough to show
  for (int i = 0; i < kMinSamples - 1; ++i) {
    feed(r, kAfterS + 5, -1.0, 12.6, 0.004);
    feed(r, kAfterS + 5, -11.0, 12.6, 0.004);
  }
  EXPECT_NEAR(r.medianMohm(), 4.0, 1e-6);
  EXPECT_NEAR(r.spreadMohm(), 0.0, 1e-6);
}

TEST(ResistanceEstimator, AStepJustUnderTheSmallestIsNotMeasured) {
  ResistanceEstimator r;
  feed(r, kAfterChargeS + kWindowS, -1.0, 12.6, 0.004);
  // 200 Ah: the smallest step is max(2 A, C/100) = 2 A, a fridge compressor's.
  EXPECT_EQ(feed(r, kAfterS + 5, -2.9, 12.6, 0.004), 0);  // 1.9 A < 2 A
  EXPECT_EQ(feed(r, kAfterS + 5, -1.0, 12.6, 0.004), 0);
  EXPECT_EQ(feed(r, kAfterS + 5, -3.1, 12.6, 0.004), 1);  // 2.1 A
  EXPECT_NEAR(r.ledger().samples_mohm[0], 4.0, 1e-6);
}

TEST(ResistanceEstimator, OnABigBankTheSmallestStepIsAHundredthOfItsCapacity) {
  ResistanceEstimator r;
  const double ah = 600.0;  // C/100 = 6 A
  feed(r, kAfterChargeS + kWindowS, -1.0, 12.6, 0.001, 25.0, ah);
  EXPECT_EQ(feed(r, kAfterS + 5, -6.9, 12.6, 0.001, 25.0, ah), 0);  // 5.9 A
  EXPECT_EQ(feed(r, kAfterS + 5, -1.0, 12.6, 0.001, 25.0, ah), 0);
  EXPECT_EQ(feed(r, kAfterS + 5, -7.1, 12.6, 0.001, 25.0, ah), 1);  // 6.1 A
}

TEST(ResistanceEstimator, NoStepIsMeasuredWhileOrSoonAfterCharging) {
  ResistanceEstimator r;
  feed(r, kAfterChargeS + kWindowS, 10.0, 13.4, 0.004);  // charging
  EXPECT_EQ(feed(r, kAfterS + 5, -10.0, 12.6, 0.004), 0);
  EXPECT_EQ(feed(r, kAfterS + 5, -1.0, 12.6, 0.004), 0);  // still within kAfterChargeS
}

TEST(ResistanceEstimator, AnUnsteadyHoldIsNotMeasured) {
  ResistanceEstimator r;
  feed(r, kAfterChargeS + kWindowS, -1.0, 12.6, 0.004);
  feed(r, 60, -11.0, 12.6, 0.004);
  EXPECT_EQ(feed(r, 70, -20.0, 12.6, 0.004), 0);  // a second step inside the hold
}

TEST(ResistanceEstimator, SamplesAreCorrectedTo25Degrees) {
  // At 0 degC the bank's R is temperatureFactor(0) x R25.
  const double k0 = ResistanceEstimator::temperatureFactor(0.0);
  EXPECT_NEAR(ResistanceEstimator::temperatureFactor(-20.0), 2.75, 0.01);  // docs/sources.md P3.4
  ResistanceEstimator r;
  feed(r, kAfterChargeS + kWindowS, -1.0, 12.6, 0.004 * k0, 0.0);
  for (int i = 0; i < kMinSamples; ++i) {
    feed(r, kAfterS + 5, -11.0, 12.6, 0.004 * k0, 0.0);
    feed(r, kAfterS + 5, -1.0, 12.6, 0.004 * k0, 0.0);
  }
  EXPECT_NEAR(r.medianMohm(), 4.0, 1e-6);
  EXPECT_NEAR(r.ohmsAt(0.0), 0.004 * k0, 1e-9);
}

TEST(ResistanceEstimator, ASavedRingComesBackWithoutItsDamagedSamples) {
  ResistanceLedger l;
  l.count = 6;
  l.samples_mohm = {3.0, 3.2, std::nan(""), 3.1, -1.0, 3.3};
  ResistanceEstimator r;
  r.restore(l);
  EXPECT_EQ(r.samples(), 4);
  EXPECT_TRUE(std::isnan(r.medianMohm()));  // 4 < kMinSamples
  l.count = 99;
  r.restore(l);
  EXPECT_EQ(r.samples(), 0);
}

}  // namespace
}  // namespace xr
