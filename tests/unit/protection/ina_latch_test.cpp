// InaLatch on its own: latches on one alert sample, releases only at its
// checks (3 s, then every 10 s), suppresses the disagreement after release.
#include "protection/ina_latch.h"

#include <gtest/gtest.h>

#include "params/constants.h"
#include "part_log.h"

namespace xr::test {
namespace {

struct LatchRig {
  Params p;
  InaLatch latch;
  PartLog log;
  void tick(bool alert, TimeNs dt = fromMs(5)) {
    log.t += dt;
    latch.update({alert, 13.5}, p, log.at());
    log.collect();
  }
};

TEST(InaLatchPart, OneAlertSampleLatchesNoneDoesNot) {
  LatchRig r;
  for (int i = 0; i < 100; ++i) r.tick(false);
  EXPECT_FALSE(r.latch.latched());
  r.tick(true);
  EXPECT_TRUE(r.latch.latched());
  EXPECT_EQ(r.log.count(EventCode::InaLatchSet, Reason::REASON_INA_OVERVOLTAGE), 1u);
  EXPECT_EQ(r.log.trip.reason, Reason::REASON_INA_OVERVOLTAGE);
}

TEST(InaLatchPart, ReleasesAtTheThreeSecondCheckNotBefore) {
  LatchRig r;
  r.tick(true);
  r.tick(false, fromMs(k::INA_LATCH_RELEASE_CHECK_MS) - fromMs(10));
  EXPECT_TRUE(r.latch.latched());  // just before the check
  r.tick(false, fromMs(10));
  EXPECT_FALSE(r.latch.latched());  // at the check
  EXPECT_EQ(r.log.count(EventCode::InaLatchCleared), 1u);
  // The disagreement detectors look away for the suppression window after it.
  EXPECT_TRUE(r.latch.suppressesDisagreement(r.log.t + fromMs(k::INA_OV_DISAGREE_SUPPRESS_MS) - 1));
  EXPECT_FALSE(r.latch.suppressesDisagreement(r.log.t + fromMs(k::INA_OV_DISAGREE_SUPPRESS_MS)));
}

TEST(InaLatchPart, StillAssertedAtTheCheckWaitsTenSecondsMore) {
  LatchRig r;
  r.tick(true);
  r.tick(true, fromMs(k::INA_LATCH_RELEASE_CHECK_MS));
  r.tick(false, fromMs(k::INA_LATCH_RECHECK_MS) - fromMs(10));
  EXPECT_TRUE(r.latch.latched());
  r.tick(false, fromMs(10));
  EXPECT_FALSE(r.latch.latched());
}

TEST(InaLatchPart, DisconnectedInaNeverLatches) {
  LatchRig r;
  r.p.INADisconnected = true;
  r.tick(true);
  EXPECT_FALSE(r.latch.latched());
  EXPECT_EQ(r.log.count(EventCode::InaLatchSet), 0u);
}

}  // namespace
}  // namespace xr::test
