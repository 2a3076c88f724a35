// A Victron GX's DVCC limits beside a BMS's (core/dvcc_limits.h): the lower of
// each wins, a silent source makes the pair stale, and the values a GX may
// send are checked against the BMS decoders' ranges.
#include "core/dvcc_limits.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "control/bms_limiter.h"

namespace xr {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

BmsLimits source(BmsSource s, TimeNs stamp, double cvl, double ccl) {
  BmsLimits b;
  b.cvlV = cvl;
  b.cclA = ccl;
  b.source = s;
  b.stamp = stamp;
  return b;
}

TEST(DvccLimits, NoDvccLeavesTheBmsLimitsAlone) {
  const BmsLimits b = source(BmsSource::Can, fromSec(3), 14.2, 80);
  const BmsLimits m = withDvcc(b, BmsLimits{});
  EXPECT_EQ(m.source, BmsSource::Can);
  EXPECT_DOUBLE_EQ(m.cvlV, 14.2);
  EXPECT_DOUBLE_EQ(m.cclA, 80);
  EXPECT_EQ(m.stamp, fromSec(3));
}

TEST(DvccLimits, DvccAloneIsTheSource) {
  const BmsLimits m = withDvcc(BmsLimits{}, source(BmsSource::VictronGx, fromSec(2), kNaN, 20));
  EXPECT_EQ(m.source, BmsSource::VictronGx);
  EXPECT_DOUBLE_EQ(m.cclA, 20);
  EXPECT_TRUE(std::isnan(m.cvlV));
}

TEST(DvccLimits, TheLowerOfEachWinsSoDvccNeverRaisesTheBms) {
  const BmsLimits bms = source(BmsSource::VictronGx, fromSec(5), 14.0, 50);
  const BmsLimits lower = withDvcc(bms, source(BmsSource::VictronGx, fromSec(6), 13.8, 20));
  EXPECT_DOUBLE_EQ(lower.cvlV, 13.8);
  EXPECT_DOUBLE_EQ(lower.cclA, 20);
  const BmsLimits higher = withDvcc(bms, source(BmsSource::VictronGx, fromSec(6), 14.6, 200));
  EXPECT_DOUBLE_EQ(higher.cvlV, 14.0);
  EXPECT_DOUBLE_EQ(higher.cclA, 50);
}

TEST(DvccLimits, ABmsWithoutCclKeepsTheFallbackCapWhateverDvccSays) {
  const BmsLimits m = withDvcc(source(BmsSource::Can, fromSec(5), 14.0, kNaN),
                               source(BmsSource::VictronGx, fromSec(5), kNaN, 150));
  EXPECT_TRUE(std::isnan(m.cclA));  // the limiter then applies BmsFallbackCapA
  Params p;
  BmsLimiter l;
  EventBatch ev;
  l.update(m, fromSec(5), 0, kNaN, p, ev);
  EXPECT_DOUBLE_EQ(l.batteryCapA(), p.BmsFallbackCapA);
}

TEST(DvccLimits, EitherSourceGoingSilentMakesThePairStale) {
  const BmsLimits fresh = source(BmsSource::Can, fromSec(20), 14.0, 50);
  const BmsLimits oldDvcc = source(BmsSource::VictronGx, fromSec(10), 14.0, 20);
  const BmsLimits m = withDvcc(fresh, oldDvcc);
  EXPECT_EQ(m.stamp, fromSec(10));
  Params p;  // BmsStaleS 5 s
  BmsLimiter l;
  EventBatch ev;
  l.update(m, fromSec(20), 0, kNaN, p, ev);
  EXPECT_TRUE(l.stale());
  EXPECT_DOUBLE_EQ(l.batteryCapA(), p.BmsFallbackCapA);
  // A BMS never heard (stamp 0) stays never heard beside DVCC.
  EXPECT_EQ(withDvcc(source(BmsSource::Can, 0, kNaN, kNaN), oldDvcc).stamp, 0);
}

TEST(DvccLimits, DvccCapsTheBatteryCurrentThroughTheLimiterAndGoesStaleAfterBmsStaleS) {
  Params p;
  BmsLimiter l;
  EventBatch ev;
  const BmsLimits d = withDvcc(BmsLimits{}, source(BmsSource::VictronGx, fromSec(1), 14.2, 20));
  l.update(d, fromSec(1), 30, kNaN, p, ev);
  EXPECT_EQ(l.state(), BmsState::OK);
  EXPECT_DOUBLE_EQ(l.batteryCapA(), 20);
  EXPECT_DOUBLE_EQ(l.cvlCeilingV(), 14.2);
  l.update(d, fromSec(1) + fromSec(p.BmsStaleS), 20, kNaN, p, ev);  // at the threshold: not yet
  EXPECT_FALSE(l.stale());
  l.update(d, fromSec(1) + fromSec(p.BmsStaleS) + fromSec(0.01), 20, kNaN, p, ev);
  EXPECT_TRUE(l.stale());
}

TEST(DvccLimits, ValuesOutsideTheBmsRangesAreRefused) {
  EXPECT_TRUE(dvccVoltageRefusal(kNaN).empty());  // not sent
  EXPECT_TRUE(dvccVoltageRefusal(8.0).empty());
  EXPECT_TRUE(dvccVoltageRefusal(70.0).empty());
  EXPECT_FALSE(dvccVoltageRefusal(7.99).empty());
  EXPECT_FALSE(dvccVoltageRefusal(70.01).empty());
  EXPECT_FALSE(dvccVoltageRefusal(std::numeric_limits<double>::infinity()).empty());
  EXPECT_TRUE(dvccCurrentRefusal(0.0).empty());
  EXPECT_TRUE(dvccCurrentRefusal(2000.0).empty());
  EXPECT_FALSE(dvccCurrentRefusal(-0.01).empty());
  EXPECT_FALSE(dvccCurrentRefusal(2000.01).empty());
  EXPECT_FALSE(dvccCurrentRefusal(-std::numeric_limits<double>::infinity()).empty());
}

}  // namespace
}  // namespace xr
