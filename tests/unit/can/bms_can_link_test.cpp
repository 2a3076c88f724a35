// BmsCanLink: frames from a (simulated) BMS become posted limits; bad frames
// are counted and reported at most once per 30 s, less often as an incident
// goes on; the candump log holds
// every frame.
#include "canlink/bms_can_link.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "drivers/can/candump_log.h"
#include "drivers/can/sim_can_bus.h"

namespace xr::canlink {
namespace {

struct LinkRig {
  can::SimCanSegment seg;
  can::SimCanNode& bms = seg.attach();
  can::SimCanNode& us = seg.attach();
  std::vector<BmsLimits> posted;
  std::vector<std::string> reports;
  BmsCanLink link{us, can::BmsProtocol::Victron, "can0", [this](const BmsLimits& l) { posted.push_back(l); },
                  [this](const std::string& r) { reports.push_back(r); }};
};

TEST(BmsCanLink, PostsLimitsWhenTheyArrive) {
  LinkRig r;
  r.link.poll(fromSec(1));
  EXPECT_TRUE(r.posted.empty());  // nothing heard: nothing posted (the limiter times out)
  r.bms.send(can::encode351(14.2, 60, 100, 12));
  r.bms.send(can::encode355(70, 100));
  r.link.poll(fromSec(2));
  ASSERT_EQ(r.posted.size(), 1u);  // one post per poll with news
  EXPECT_DOUBLE_EQ(r.posted[0].cclA, 60.0);
  EXPECT_DOUBLE_EQ(r.posted[0].socPct, 70.0);
  EXPECT_EQ(r.posted[0].stamp, fromSec(2));
}

TEST(BmsCanLink, BadFramesAreCountedIgnoredAndReportedRateLimited) {
  LinkRig r;
  r.bms.send(can::encode351(14.2, 60, 100, 12));
  r.link.poll(fromSec(1));
  CanFrame bad = can::encode351(14.2, 0, 100, 12);
  bad.data[2] = 0x60;  // CCL 6 000 A
  bad.data[3] = 0xEA;
  for (int i = 0; i < 5; ++i) {
    r.bms.send(bad);
    r.link.poll(fromSec(2 + i));
  }
  EXPECT_EQ(r.link.decoder().rejected(), 5u);
  ASSERT_EQ(r.reports.size(), 1u);  // one report within 30 s
  EXPECT_NE(r.reports[0].find("0x351"), std::string::npos);
  EXPECT_EQ(r.posted.size(), 1u);  // the bad frames never posted
  EXPECT_DOUBLE_EQ(r.posted.back().cclA, 60.0);
  r.bms.send(bad);
  r.link.poll(fromSec(40));  // 30 s on: the next report counts what came since
  ASSERT_EQ(r.reports.size(), 2u);
  EXPECT_NE(r.reports[1].find("5 bad frame"), std::string::npos);
}

// Ten hours of a bad frame every second (a BMS that keeps sending what the
// decoder drops): a handful of lines in the first hour, one an hour after,
// and every frame still in the counts.
TEST(BmsCanLink, RepeatedBadFramesAreAtMostTenLinesAnHourWithTheirCount) {
  LinkRig r;
  CanFrame bad = can::encode351(71.0, 10, 100, 12);  // CVL out of range
  std::vector<std::size_t> perHour(10, 0);
  for (int s = 0; s < 10 * 3600; ++s) {
    r.bms.send(bad);
    const std::size_t before = r.reports.size();
    r.link.poll(fromSec(s));
    perHour[s / 3600] += r.reports.size() - before;
  }
  for (std::size_t h = 0; h < perHour.size(); ++h) EXPECT_LE(perHour[h], 10u) << "hour " << h;
  EXPECT_GE(perHour[0], 2u);  // the first at once, then a few more while it is new
  EXPECT_LE(perHour[5], 2u);  // then about one an hour
  std::uint64_t counted = 0;
  for (const auto& line : r.reports) counted += std::stoull(line.substr(line.find(": ") + 2));
  EXPECT_LE(counted, r.link.decoder().rejected());
  EXPECT_GE(counted, 9u * 3600u);  // the counts carry (almost) every frame: only the last hour's tail waits
  // Quiet for ten minutes ends the incident: the next bad frame is told at once.
  const int quietEnd = 10 * 3600 + 700;
  r.link.poll(fromSec(10 * 3600 + 100));
  r.link.poll(fromSec(quietEnd - 1));
  const std::size_t before = r.reports.size();
  r.bms.send(bad);
  r.link.poll(fromSec(quietEnd));
  EXPECT_EQ(r.reports.size(), before + 1);
}

// Another kind of bad frame in the same incident is told at once, once.
TEST(BmsCanLink, ANewKindOfBadFrameIsToldAtOnce) {
  LinkRig r;
  CanFrame cvl = can::encode351(71.0, 10, 100, 12);  // CVL out of range
  for (int s = 0; s < 200; ++s) {
    r.bms.send(cvl);
    r.link.poll(fromSec(s));
  }
  const std::size_t before = r.reports.size();
  CanFrame shortDlc = can::encode351(14.2, 10, 100, 12);
  shortDlc.dlc = 4;
  r.bms.send(shortDlc);
  r.link.poll(fromSec(200));
  ASSERT_EQ(r.reports.size(), before + 1);
  EXPECT_NE(r.reports.back().find("short DLC"), std::string::npos) << r.reports.back();
  for (int s = 201; s < 260; ++s) {  // both kinds again: nothing new to tell at once
    r.bms.send(s % 2 ? cvl : shortDlc);
    r.link.poll(fromSec(s));
  }
  EXPECT_LE(r.reports.size(), before + 2);
}

TEST(BmsCanLink, WithAnEventSinkTheReportIsAnEvent) {
  LinkRig r;
  std::vector<Event> events;
  r.link.setPostEvent([&](const Event& e) { events.push_back(e); });
  CanFrame bad = can::encode351(71.0, 10, 100, 12);  // CVL out of range
  r.bms.send(bad);
  r.link.poll(fromSec(5));
  EXPECT_TRUE(r.reports.empty());
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].code, EventCode::BmsBadFrames);
  EXPECT_DOUBLE_EQ(events[0].a, 1.0);
  EXPECT_DOUBLE_EQ(events[0].b, 0x351);
  EXPECT_EQ(static_cast<BmsReject>(events[0].detail), BmsReject::CvlRange);
  EXPECT_EQ(describe(events[0]), "BMS CAN: 1 bad frame(s) ignored (last: 0x351, CVL out of range)");
  EXPECT_EQ(r.link.lastAccepted(), 0);
}

TEST(BmsCanLink, LogsEveryFrameInCandumpFormat) {
  LinkRig r;
  std::ostringstream log;
  r.link.setLog(&log);
  r.bms.send(can::encode351(14.0, 50, 50, 0));
  r.link.poll(fromSec(3));
  const auto line = can::parseCandump(log.str());
  ASSERT_TRUE(line);
  EXPECT_EQ(line->interface, "can0");
  EXPECT_EQ(line->frame, can::encode351(14.0, 50, 50, 0));
  EXPECT_EQ(log.str(), "(3.000000) can0 351#8C00F401F4010000\n");
}

}  // namespace
}  // namespace xr::canlink
