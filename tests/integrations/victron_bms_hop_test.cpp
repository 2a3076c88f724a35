// The Victron GX's limits into Handoffs::bms (docs/integrations.md): the mapping, the
// stamp on the control clock, and that a poll bringing nothing new leaves
// the stamp alone (so a silent GX goes stale like a silent CAN BMS).
#include "integrations/victron_bms_hop.h"

#include <gtest/gtest.h>

#include <cmath>

#include "control/bms_limiter.h"

namespace xr::integrations {
namespace {

struct HopTest : ::testing::Test {
  Params params;
  rt::Handoffs h{params};
  VictronBmsHop hop{h};

  void controlClockAt(double s) {
    rt::RuntimeSnapshot snap;
    snap.telemetry.now = fromSec(s);
    h.snapshot.store(snap);
  }
  BmsLimits posted() { return h.bms.load(); }
  static VictronLimits fresh(double ccl, std::uint64_t updates) {
    VictronLimits v;
    v.cvl_v = 14.2;
    v.ccl_a = ccl;
    v.soc_pct = 81.5;
    v.temp_c = 22.5;
    v.allowToCharge = 1;
    v.limitUpdates = updates;
    v.ageS = 0;
    v.stale = false;
    return v;
  }
};

TEST_F(HopTest, MapsEveryField) {
  const BmsLimits b = toBmsLimits(fresh(50, 1), fromSec(7));
  EXPECT_DOUBLE_EQ(b.cvlV, 14.2);
  EXPECT_DOUBLE_EQ(b.cclA, 50);
  EXPECT_DOUBLE_EQ(b.socPct, 81.5);
  EXPECT_DOUBLE_EQ(b.tempC, 22.5);
  EXPECT_TRUE(b.chargeAllowed);
  EXPECT_EQ(b.source, BmsSource::VictronGx);
  EXPECT_EQ(b.stamp, fromSec(7));
  VictronLimits no = fresh(50, 1);
  no.allowToCharge = 0;
  EXPECT_FALSE(toBmsLimits(no, 1).chargeAllowed);
  no.allowToCharge = -1;  // not known: the BMS has not said no
  EXPECT_TRUE(toBmsLimits(no, 1).chargeAllowed);
  const BmsLimits unknown = toBmsLimits(VictronLimits{}, 0);
  EXPECT_TRUE(std::isnan(unknown.cclA));
  EXPECT_TRUE(std::isnan(unknown.cvlV));
}

TEST_F(HopTest, StampsEachNewLimitOnTheControlClock) {
  controlClockAt(100.0);
  hop(fresh(50, 1));
  EXPECT_EQ(posted().stamp, fromSec(100.0));
  EXPECT_DOUBLE_EQ(posted().cclA, 50);
  controlClockAt(103.5);
  hop(fresh(40, 2));
  EXPECT_EQ(posted().stamp, fromSec(103.5));
  EXPECT_DOUBLE_EQ(posted().cclA, 40);
}

TEST_F(HopTest, APollWithNothingNewKeepsTheArrivalStamp) {
  controlClockAt(100.0);
  hop(fresh(50, 1));
  const auto posts = hop.posts();
  controlClockAt(104.0);
  VictronLimits later = fresh(50, 1);  // same update count: nothing arrived
  later.ageS = 4.0;
  later.stale = false;
  hop(later);
  EXPECT_EQ(posted().stamp, fromSec(100.0));
  EXPECT_EQ(hop.posts(), posts) << "nothing changed, nothing stored";
}

// A SoC or AllowToCharge change is passed on at once but does not refresh
// the limits' stamp.
TEST_F(HopTest, OtherValuesPassWithoutRefreshingTheStamp) {
  controlClockAt(100.0);
  hop(fresh(50, 1));
  controlClockAt(102.0);
  VictronLimits v = fresh(50, 1);
  v.allowToCharge = 0;
  hop(v);
  EXPECT_FALSE(posted().chargeAllowed);
  EXPECT_EQ(posted().stamp, fromSec(100.0));
}

TEST_F(HopTest, BeforeTheFirstTickTheLimitsAreNotStamped) {
  hop(fresh(50, 1));  // no snapshot yet: telemetry.now == 0
  EXPECT_EQ(posted().stamp, 0);
  controlClockAt(5.0);
  hop(fresh(50, 2));
  EXPECT_EQ(posted().stamp, fromSec(5.0));
}

// Through the limiter: the hop's limits cap the battery current, and the
// same limits with no new arrival go stale after BmsStaleS on the control
// clock (REASON_BMS_STALE, BmsFallbackCapA), exactly at the threshold.
TEST_F(HopTest, TheLimiterFollowsThenFallsBackAtBmsStaleS) {
  Params p;
  p.BmsLimitsEnabled = true;
  p.BmsStaleS = 5.0;
  p.BmsFallbackCapA = 10.0;
  BmsLimiter lim;
  EventBatch ev;
  controlClockAt(100.0);
  hop(fresh(40, 1));
  lim.update(h.bms.load(), fromSec(100.0), 60.0, kNoValue, p, ev);
  EXPECT_DOUBLE_EQ(lim.batteryCapA(), 40.0);
  EXPECT_FALSE(lim.stale());
  lim.update(h.bms.load(), fromSec(105.0), 40.0, kNoValue, p, ev);  // at the threshold: still fresh
  EXPECT_FALSE(lim.stale());
  EXPECT_DOUBLE_EQ(lim.batteryCapA(), 40.0);
  lim.update(h.bms.load(), fromSec(105.01), 40.0, kNoValue, p, ev);  // just past it
  EXPECT_TRUE(lim.stale());
  EXPECT_DOUBLE_EQ(lim.batteryCapA(), 10.0);
  controlClockAt(106.0);
  hop(fresh(40, 2));  // the GX answers again
  lim.update(h.bms.load(), fromSec(106.0), 10.0, kNoValue, p, ev);
  EXPECT_FALSE(lim.stale());
  EXPECT_DOUBLE_EQ(lim.batteryCapA(), 40.0);
}

}  // namespace
}  // namespace xr::integrations
