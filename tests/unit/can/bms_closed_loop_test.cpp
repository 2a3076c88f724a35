// The whole BMS path against the test plant: the simulated BMS's frames ->
// BmsDecoder -> BmsLimits -> Regulator -> plant -> the BMS's view of the
// battery. The BMS opens its contactor if its limits are ignored for 3 s.
#include <gtest/gtest.h>

#include <cmath>

#include "can/bms_codec.h"
#include "drivers/sim/bms/sim_bms.h"
#include "reg_rig.h"

namespace xr {
namespace {

struct BmsPath {
  test::RegRig r;
  sim::SimBms bms;
  can::BmsDecoder decoder{can::BmsProtocol::Victron};
  double cclChangedAt = -1.0;  // when the decoded CCL last changed (s)

  explicit BmsPath(bool follow) : r(params(follow)) {
    r.plant.house = 8.0;
    r.plant.Vocv = 12.6;  // far below CVL: current-limited
  }
  static Params params(bool follow) {
    Params p;
    p.BmsLimitsEnabled = follow;
    return p;
  }
  sim::SimBmsTruth truth() const { return {r.plant.V(), r.plant.Ibat(), 60.0, 20.0}; }
  // Runs `seconds`; returns the largest battery current seen after `fromS`.
  double run(double seconds, double fromS = 1e9) {
    double worst = -1e9;
    const long n = std::lround(seconds / 0.0025);
    for (long i = 0; i < n; ++i) {
      for (const CanFrame& f : bms.step(r.now, truth())) {
        const double before = decoder.limits().cclA;
        decoder.feed(f, r.now);
        if (decoder.limits().cclA != before) cclChangedAt = toSec(r.now);
      }
      r.bms = decoder.limits();
      r.tick();
      if (i * 0.0025 >= fromS) worst = std::max(worst, r.plant.Ibat());
    }
    return worst;
  }
};

TEST(SimBms, CclTapersNearFullAndWhenCold) {
  sim::SimBms b;
  EXPECT_DOUBLE_EQ(b.ccl({13.3, 10, 50, 25}), 100.0);
  EXPECT_DOUBLE_EQ(b.ccl({13.3, 10, 95, 25}), 20.0);
  EXPECT_NEAR(b.ccl({13.3, 10, 50, 5}), 50.0, 1e-9);
  EXPECT_DOUBLE_EQ(b.ccl({13.3, 10, 50, 0}), 0.0);
  EXPECT_FALSE(b.warning({14.29, 10, 50, 25}));
  EXPECT_TRUE(b.warning({14.31, 10, 50, 25}));  // CVL 14.2 + 0.1
}

TEST(SimBms, OpensWhenIgnoredForMoreThanOpenAfterS) {
  sim::SimBms b;
  b.forcedCclA = 10;
  const sim::SimBmsTruth over{13.3, 16, 50, 25};  // CCL + 6 A
  b.step(fromSec(1), over);
  b.step(fromSec(4), over);
  EXPECT_FALSE(b.contactorOpen());  // exactly 3 s
  b.step(fromSec(4) + fromMs(10), over);
  EXPECT_TRUE(b.contactorOpen());
  sim::SimBms c;
  c.forcedCclA = 10;
  c.step(fromSec(1), {13.3, 14.9, 50, 25});  // within the margin: never ignored
  c.step(fromSec(10), {13.3, 14.9, 50, 25});
  EXPECT_FALSE(c.contactorOpen());
}

TEST(BmsPathClosedLoop, CclStepIsMetWithinOneSecond) {
  BmsPath p(true);
  p.bms.forcedCclA = 40;
  p.run(30);
  ASSERT_GT(p.r.plant.Ibat(), 30.0);
  p.bms.forcedCclA = 10;
  p.run(0.6);  // the next 0x351 carries the step
  ASSERT_GT(p.cclChangedAt, 0.0);
  const double sinceStep = toSec(p.r.now) - p.cclChangedAt;
  const double worst = p.run(5, std::max(0.0, 1.0 - sinceStep));
  EXPECT_LE(worst, 10.0 + 2.0);
  EXPECT_FALSE(p.bms.contactorOpen());
}

TEST(BmsPathClosedLoop, AWarningRampsDownBeforeTheBmsOpens) {
  BmsPath p(true);
  p.run(30);
  ASSERT_GT(p.r.plant.Ibat(), 30.0);
  p.bms.forcedWarning = true;
  p.run(10);
  EXPECT_FALSE(p.bms.contactorOpen());
  EXPECT_LE(p.r.plant.Ibat(), 2.0);
  EXPECT_EQ(p.r.out->telemetry.bms_state, BmsState::WARNING);
}

TEST(BmsPathClosedLoop, IgnoringTheBmsOpensIt) {
  // The same warning with the limits not followed: the BMS opens (what the
  // ramp-down above prevents).
  BmsPath p(false);
  p.run(30);
  p.bms.forcedWarning = true;
  p.run(10);
  EXPECT_TRUE(p.bms.contactorOpen());
}

TEST(BmsPathClosedLoop, SilentBmsFallsBackWithinBmsStaleSPlusOne) {
  BmsPath p(true);
  p.run(30);
  ASSERT_GT(p.r.plant.Ibat(), 30.0);
  p.bms.talking = false;
  const double stale = p.r.p.BmsStaleS;
  const double worst = p.run(stale + 6.0, stale + 1.0);
  EXPECT_LE(worst, p.r.p.BmsFallbackCapA + 2.0);
  EXPECT_EQ(p.r.out->telemetry.reason, Reason::REASON_BMS_STALE);
}

}  // namespace
}  // namespace xr
