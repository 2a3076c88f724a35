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
  can::BmsDecoder decoder;
  double cclChangedAt = -1.0;  // when the decoded CCL last changed (s)
  // Over a run(): the highest cell the BMS reported, whether it warned, the
  // lowest battery current, and whether the limiter ramped on a high cell.
  double worstCell = 0.0, leastIbat = 1e9;
  bool bmsWarned = false, cellRamp = false;

  explicit BmsPath(bool follow, can::BmsProtocol protocol = can::BmsProtocol::Victron,
                   double cellHighV = 3.60)
      : r(params(follow, cellHighV)), decoder(protocol) {
    bms.rec = protocol == can::BmsProtocol::Rec;
    r.plant.house = 8.0;
    r.plant.Vocv = 12.6;  // far below CVL: current-limited
  }
  static Params params(bool follow, double cellHighV) {
    Params p;
    p.BmsLimitsEnabled = follow;
    p.BmsCellHighV = cellHighV;
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
      worstCell = std::max(worstCell, bms.cellMaxV(truth()));
      bmsWarned |= bms.warning(truth());
      leastIbat = std::min(leastIbat, r.plant.Ibat());
      cellRamp |= r.out->telemetry.bms_state == BmsState::WARNING;
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

TEST(SimBms, RecSendsItsCellsAndWarnsOnAHighCell) {
  sim::SimBms b;
  b.rec = true;
  b.cellSpreadV = 0.1;
  const auto frames = b.step(0, {14.0, 20, 87.25, 18});
  can::BmsDecoder d(can::BmsProtocol::Rec);
  int n373 = 0;
  for (const CanFrame& f : frames) {
    EXPECT_EQ(d.feed(f, 0), can::BmsFrameResult::Accepted) << std::hex << f.id;
    n373 += f.id == 0x373;
  }
  EXPECT_EQ(n373, 1);
  EXPECT_NEAR(d.limits().cellMaxV, 3.6, 1e-9);  // 14.0 / 4 + 0.1
  EXPECT_NEAR(d.limits().cellMinV, 3.4, 1e-9);
  EXPECT_DOUBLE_EQ(d.limits().cellTempMaxC, 18.0);
  EXPECT_NEAR(d.limits().socPct, 87.25, 1e-9);
  EXPECT_FALSE(b.warning({14.2, 10, 50, 25}));  // 3.65: at its limit, not over
  EXPECT_TRUE(b.warning({14.21, 10, 50, 25}));
}

TEST(BmsPathClosedLoop, RecHighCellIsHeldAtBmsCellHighVBeforeTheBmsWarns) {
  BmsPath p(true, can::BmsProtocol::Rec);
  p.run(30);
  const double chargingA = p.r.plant.Ibat();
  ASSERT_GT(chargingA, 30.0);
  ASSERT_FALSE(p.cellRamp);
  // An unbalanced pack: its highest cell 15 mV over BmsCellHighV at this
  // charge, the pack still far under CVL.
  p.bms.cellSpreadV = 3.615 - p.r.plant.V() / 4;
  p.worstCell = 0;
  p.leastIbat = 1e9;
  p.run(60);
  // A constant voltage on that cell (docs/deviations.md "The highest cell
  // held at its limit"): the charge goes on, smaller, never switched off,
  // and the cell settles at the limit.
  // This test plant's small bank fills fast, so the constant-voltage
  // current tapers toward zero within the minute, as it should.
  EXPECT_FALSE(p.cellRamp);  // no warning ramp to zero
  EXPECT_TRUE(p.r.out->fieldEnable);
  EXPECT_GT(p.r.plant.Ibat(), 0.2);  // still charging at the end
  EXPECT_LT(p.r.plant.Ibat(), chargingA);
  EXPECT_NEAR(p.bms.cellMaxV(p.truth()), 3.60, 0.01);
  EXPECT_LE(p.worstCell, 3.65);  // the BMS's own cell limit never reached
  EXPECT_FALSE(p.bmsWarned);
  EXPECT_FALSE(p.bms.contactorOpen());
  // The same pack with BmsCellHighV = 0 (off): the charge goes on until the
  // high cell passes the BMS's own limit and it warns (the warning's ramp
  // then stops the charge, later and with the BMS a step from opening).
  BmsPath q(true, can::BmsProtocol::Rec, 0.0);
  q.run(30);
  q.bms.cellSpreadV = p.bms.cellSpreadV;
  q.run(20);
  EXPECT_GT(q.worstCell, 3.65);
  EXPECT_TRUE(q.bmsWarned);
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
