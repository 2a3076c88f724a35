// ShuntGainCorrector on its own (docs/batteries.md "Auto shunt-gain
// correction"): the error limit at its threshold and just above, the 2 %
// step, the 24 h rate limit, the guards, the reset.
#include "battery/shunt_gain.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xr {
namespace {

constexpr TimeNs kT0 = fromSec(1000.0);

GainCorrectionInput fullWith(double countAh, TimeNs now = kT0) {
  GainCorrectionInput in;
  in.now = now;
  in.enabled = true;
  in.referenceValid = true;
  in.countSinceReference_Ah = countAh;
  in.expectedCapacity_Ah = 200.0;
  return in;
}

TEST(ShuntGainCorrector, ACountShortOfTheCapacityRaisesTheGainByAtMostTwoPercent) {
  ShuntGainCorrector g;
  EventBatch ev;
  g.atFullCharge(fullWith(180.0), ev);  // 10 % short
  EXPECT_EQ(g.lastGuard(), GainGuard::Applied);
  EXPECT_DOUBLE_EQ(g.factor(), 1.0 + battery_k::MAX_GAIN_ADJUSTMENT_PER_CYCLE);
  EXPECT_DOUBLE_EQ(g.corrected(10.0), 10.0 * g.factor());
  ASSERT_EQ(ev.count, 1u);
  EXPECT_EQ(ev.items[0].code, EventCode::ShuntGainCorrected);
}

TEST(ShuntGainCorrector, AnErrorAtTheLimitCorrectsJustAboveItIsAFault) {
  ShuntGainCorrector at, above;
  EventBatch ev;
  at.atFullCharge(fullWith(200.0 * (1.0 - battery_k::MAX_REASONABLE_ERROR)), ev);
  EXPECT_EQ(at.lastGuard(), GainGuard::Applied);
  above.atFullCharge(fullWith(200.0 * (1.0 - battery_k::MAX_REASONABLE_ERROR) - 0.1), ev);
  EXPECT_EQ(above.lastGuard(), GainGuard::ErrorTooLarge);
  EXPECT_DOUBLE_EQ(above.factor(), 1.0);
}

TEST(ShuntGainCorrector, OncePerDay) {
  ShuntGainCorrector g;
  EventBatch ev;
  g.atFullCharge(fullWith(196.0), ev);
  ASSERT_EQ(g.lastGuard(), GainGuard::Applied);
  const double after = g.factor();
  const TimeNs day = fromMs(battery_k::MIN_GAIN_CORRECTION_INTERVAL_MS);
  g.atFullCharge(fullWith(196.0, kT0 + day - fromMs(1)), ev);
  EXPECT_EQ(g.lastGuard(), GainGuard::TooSoon);
  EXPECT_DOUBLE_EQ(g.factor(), after);
  g.atFullCharge(fullWith(196.0, kT0 + day), ev);
  EXPECT_EQ(g.lastGuard(), GainGuard::Applied);
}

TEST(ShuntGainCorrector, GuardsAndBounds) {
  ShuntGainCorrector g;
  EventBatch ev;
  GainCorrectionInput off = fullWith(190.0);
  off.enabled = false;
  g.atFullCharge(off, ev);
  EXPECT_EQ(g.lastGuard(), GainGuard::FeatureOff);
  GainCorrectionInput noRef = fullWith(190.0);
  noRef.referenceValid = false;
  g.atFullCharge(noRef, ev);
  EXPECT_EQ(g.lastGuard(), GainGuard::NoReference);
  g.atFullCharge(fullWith(battery_k::MIN_PLAUSIBLE_CAPACITY_AH - 0.1), ev);
  EXPECT_EQ(g.lastGuard(), GainGuard::ImplausibleCapacity);
  EXPECT_DOUBLE_EQ(g.factor(), 1.0);
  g.restore(battery_k::MAX_DYNAMIC_GAIN_FACTOR - 0.005);
  g.atFullCharge(fullWith(190.0), ev);
  EXPECT_DOUBLE_EQ(g.factor(), battery_k::MAX_DYNAMIC_GAIN_FACTOR);
  g.reset();
  EXPECT_DOUBLE_EQ(g.factor(), 1.0);
  g.restore(std::nan(""));
  EXPECT_DOUBLE_EQ(g.factor(), 1.0);
}

}  // namespace
}  // namespace xr
