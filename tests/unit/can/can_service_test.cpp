// The CAN service (docs/integrations.md): buses opened with retry and backoff, limits
// posted into the hand-off stamped with the caller's clock, every frame in
// the candump log.
#include "canlink/can_service.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "drivers/can/candump_log.h"
#include "drivers/can/sim_can_bus.h"
#include "drivers/can/socketcan_bus.h"

namespace xr::canlink {
namespace {

// A bus the slot may own and drop while the test keeps the real node.
struct Borrowed final : CanBus {
  CanBus& b;
  explicit Borrowed(CanBus& x) : b(x) {}
  bool send(const CanFrame& f) noexcept override { return b.send(f); }
  std::optional<CanFrame> receive(std::chrono::milliseconds t) noexcept override { return b.receive(t); }
  CanBusStats stats() const noexcept override { return b.stats(); }
};

TEST(BusSlot, AMissingBusIsRetriedWithBackoffAndReported) {
  can::SimCanSegment seg;
  can::SimCanNode& node = seg.attach();
  int attempts = 0;
  int failFor = 4;
  std::vector<std::string> reports;
  BusSlot slot(
      "can9",
      [&]() -> std::unique_ptr<CanBus> {
        ++attempts;
        if (attempts <= failFor) throw std::runtime_error("no such device");
        return std::make_unique<Borrowed>(node);
      },
      [&](const std::string& r) { reports.push_back(r); });
  // Attempts at 0, then 1 s, 2 s, 4 s later: 0, 1, 3, 7 s.
  EXPECT_EQ(slot.get(0), nullptr);
  EXPECT_EQ(attempts, 1);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_NE(reports[0].find("can9: no such device; retry in 1 s"), std::string::npos) << reports[0];
  EXPECT_EQ(slot.get(fromSec(0.99)), nullptr);
  EXPECT_EQ(attempts, 1);  // not yet
  EXPECT_EQ(slot.get(fromSec(1.0)), nullptr);
  EXPECT_EQ(attempts, 2);
  EXPECT_EQ(slot.get(fromSec(2.9)), nullptr);
  EXPECT_EQ(attempts, 2);
  EXPECT_EQ(slot.get(fromSec(3.0)), nullptr);
  EXPECT_EQ(slot.get(fromSec(6.9)), nullptr);
  EXPECT_EQ(attempts, 3);
  EXPECT_EQ(slot.get(fromSec(7.0)), nullptr);
  EXPECT_EQ(attempts, 4);
  EXPECT_NE(reports.back().find("retry in 8 s"), std::string::npos) << reports.back();
  EXPECT_FALSE(slot.takeOpened());
  EXPECT_NE(slot.get(fromSec(15.0)), nullptr);  // the fifth attempt opens it
  EXPECT_TRUE(slot.takeOpened());
  EXPECT_FALSE(slot.takeOpened());  // once per open
  EXPECT_NE(reports.back().find("open again after 4 failed attempt(s)"), std::string::npos) << reports.back();
  EXPECT_EQ(slot.failures(), 4u);
  // Lost: closed, retried from 1 s again.
  slot.lost(fromSec(20.0), "bus gone");
  EXPECT_EQ(slot.get(fromSec(20.5)), nullptr);
  EXPECT_NE(slot.get(fromSec(21.0)), nullptr);
}

TEST(BusSlot, TheBackoffStopsAtSixtySeconds) {
  int attempts = 0;
  BusSlot slot(
      "can9",
      [&]() -> std::unique_ptr<CanBus> {
        ++attempts;
        throw std::runtime_error("down");
      },
      [](const std::string&) {});
  TimeNs t = 0;
  for (int i = 0; i < 12; ++i) {
    slot.get(t);
    t += fromSec(60.0);  // one attempt per minute at most, never slower
  }
  EXPECT_EQ(attempts, 12);
}

// This machine (and CI) has no AF_CAN: the real backend's open fails with a
// clear error, which is the path a board takes with the HAT missing.
TEST(BusSlot, TheSocketCanBackendOnAMissingInterfaceIsReportedNotThrown) {
  std::vector<std::string> reports;
  BusSlot slot(
      "xrcan-missing0", [] { return std::unique_ptr<CanBus>(new can::SocketCanBus("xrcan-missing0")); },
      [&](const std::string& r) { reports.push_back(r); });
  EXPECT_EQ(slot.get(0), nullptr);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_NE(reports[0].find("xrcan-missing0"), std::string::npos) << reports[0];
}

struct ServiceRig {
  can::SimCanSegment seg;
  can::SimCanNode& bms = seg.attach();
  can::SimCanNode& us = seg.attach();
  rt::Handoffs h{Params{}};
  std::vector<std::string> reports;
  std::ostringstream log;
  double logTime = 0.0;
  can::CandumpSink sink{log, [this] { return logTime; }};
  CanService svc{h, [this](const std::string& r) { reports.push_back(r); }};
  ServiceRig() {
    svc.setLog(&sink);
    svc.setBmsBus(std::make_unique<BusSlot>("simcan0", us), can::BmsProtocol::Victron);
  }
};

TEST(CanService, PostsTheLimitsStampedWithTheCallersClock) {
  ServiceRig r;
  r.svc.poll(fromSec(1.0));
  EXPECT_EQ(r.h.bms.load().stamp, 0);  // nothing heard yet: nothing posted
  r.bms.send(can::encode351(14.1, 55.0, 100.0, 12.0));
  r.svc.poll(fromSec(2.5));
  const BmsLimits l = r.h.bms.load();
  EXPECT_EQ(l.stamp, fromSec(2.5));
  EXPECT_NEAR(l.cclA, 55.0, 1e-9);
  EXPECT_NEAR(l.cvlV, 14.1, 1e-9);
  EXPECT_EQ(l.source, BmsSource::Can);
}

TEST(CanService, TheBmsTemperatureIsTheBatteryTemperatureOnlyWhenAsked) {
  ServiceRig r;  // set up without: a battery DS18B20 writes that hand-off
  r.bms.send(can::encode356(13.3, 20.0, 17.5));
  r.svc.poll(fromSec(1.0));
  EXPECT_EQ(r.h.batteryTemp.load().stamp, 0);
  r.svc.setBmsBus(std::make_unique<BusSlot>("simcan0", r.us), can::BmsProtocol::Victron, true);
  r.bms.send(can::encode356(13.3, 20.0, 17.5));
  r.svc.poll(fromSec(2.0));
  const rt::BatteryTempHandoff t = r.h.batteryTemp.load();
  EXPECT_NEAR(t.tempC, 17.5, 1e-9);
  EXPECT_EQ(t.stamp, fromSec(2.0));
  EXPECT_EQ(t.source, BatteryTempSource::bms);
}

std::vector<Event> takeSideEvents(rt::Handoffs& h) {
  std::array<Event, rt::SideEvents::kCapacity> out;
  const std::size_t n = h.sideEvents.take(out);
  return {out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n)};
}

TEST(CanService, BadFramesNeverReachTheHandoffAndAreOneRateLimitedEvent) {
  ServiceRig r;
  r.bms.send(can::encode351(14.1, 55.0, 100.0, 12.0));
  r.svc.poll(fromSec(1.0));
  CanFrame bad = can::encode351(14.1, 6000.0, 100.0, 12.0);  // clamps to 3276.7 A: still rejected
  r.bms.send(bad);
  CanFrame shortOne = can::encode351(14.1, 20.0, 100.0, 12.0);
  shortOne.dlc = 4;
  r.bms.send(shortOne);
  r.svc.poll(fromSec(2.0));
  const BmsLimits l = r.h.bms.load();
  EXPECT_NEAR(l.cclA, 55.0, 1e-9);
  EXPECT_EQ(l.stamp, fromSec(1.0));  // the good limits stand with their time: they go stale
  ASSERT_NE(r.svc.bmsLink(), nullptr);
  EXPECT_EQ(r.svc.bmsLink()->decoder().rejected(), 2u);
  // An event for the dashboard (not a journal line of its own: the event
  // pump journals it).
  EXPECT_TRUE(r.reports.empty());
  auto ev = takeSideEvents(r.h);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].code, EventCode::BmsBadFrames);
  EXPECT_EQ(ev[0].level, EventLevel::Warning);
  EXPECT_EQ(ev[0].t, fromSec(2.0));
  EXPECT_EQ(describe(ev[0]), "BMS CAN: 2 bad frame(s) ignored (last: 0x351, short DLC)");
  // More within 30 s: counted, no event; 30 s on, one event with the count.
  for (int i = 0; i < 10; ++i) {
    r.bms.send(shortOne);
    r.svc.poll(fromSec(3.0 + i));
  }
  EXPECT_TRUE(takeSideEvents(r.h).empty());
  r.svc.poll(fromSec(32.0));
  ev = takeSideEvents(r.h);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_DOUBLE_EQ(ev[0].a, 10.0);
  EXPECT_EQ(r.h.canStatus.load().bmsBadFrames, 12u);
}

TEST(CanService, ErrorFramesAreCountedAndOneEvent) {
  ServiceRig r;
  CanFrame err;
  err.error = true;
  err.extended = true;
  err.id = 0x40;  // CAN_ERR_BUSOFF
  r.bms.send(err);
  r.bms.send(err);
  r.svc.poll(fromSec(1.0));
  auto ev = takeSideEvents(r.h);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].code, EventCode::CanErrorFrames);
  EXPECT_EQ(describe(ev[0]), "CAN BMS bus: 2 error frame(s) (last error class 0x40)");
  EXPECT_EQ(r.svc.bmsLink()->decoder().rejected(), 0u);  // not bad BMS frames
  EXPECT_EQ(r.h.canStatus.load().bmsErrorFrames, 2u);
}

TEST(CanService, ABusThatCannotOpenIsOneEventPerOutageAndOneWhenBack) {
  can::SimCanSegment seg;
  can::SimCanNode& node = seg.attach();
  rt::Handoffs h{Params{}};
  int attempts = 0;
  CanService svc(h, [](const std::string&) {});
  svc.setN2kBus(std::make_unique<BusSlot>(
                    "can1",
                    [&]() -> std::unique_ptr<CanBus> {
                      if (++attempts <= 7) throw std::runtime_error("no such device");
                      return std::make_unique<Borrowed>(node);
                    },
                    nullptr),
                35, "test");
  // Attempts at 0, 1, 3, 7, 15, 31, 63 s fail; 123 s (the 60 s ceiling) opens.
  std::vector<Event> ev;
  for (double t = 0.0; t <= 130.0; t += 0.5) {
    svc.poll(fromSec(t));
    for (const Event& e : takeSideEvents(h)) ev.push_back(e);
    if (t == 10.0) {
      const auto st = h.canStatus.load();
      EXPECT_TRUE(st.n2kConfigured);
      EXPECT_FALSE(st.n2kBusUp);
      EXPECT_FALSE(st.bmsConfigured);
    }
  }
  EXPECT_EQ(attempts, 8);
  // Down at 0 s (1st attempt), then at most one per 30 s: 31 s, 63 s.
  ASSERT_EQ(ev.size(), 4u);
  EXPECT_EQ(ev[0].code, EventCode::CanBusDown);
  EXPECT_EQ(ev[0].t, 0);
  EXPECT_EQ(ev[0].detail, 1);  // NMEA 2000
  EXPECT_EQ(describe(ev[0]),
            "CAN NMEA 2000 bus cannot be opened (1 failed attempt(s)); retry in 1 s: no NMEA 2000 output");
  EXPECT_EQ(ev[1].t, fromSec(31.0));
  EXPECT_DOUBLE_EQ(ev[1].a, 6.0);
  EXPECT_EQ(ev[2].t, fromSec(63.0));
  EXPECT_EQ(ev[3].code, EventCode::CanBusBack);
  EXPECT_EQ(ev[3].t, fromSec(123.0));  // 63 s + the 60 s ceiling
  EXPECT_EQ(describe(ev[3]), "CAN NMEA 2000 bus open again after 7 failed attempt(s)");
  const auto st = h.canStatus.load();
  EXPECT_TRUE(st.n2kBusUp);
  EXPECT_TRUE(st.n2kClaimed);
  EXPECT_EQ(st.n2kAddress, 35);
  EXPECT_GE(st.n2kTxFrames, 1u);  // the address claim at least
  EXPECT_EQ(st.n2kOpenFailures, 7u);
}

TEST(CanService, PublishesTheBmsStatus) {
  ServiceRig r;
  r.svc.poll(fromSec(1.0));
  auto st = r.h.canStatus.load();
  EXPECT_TRUE(st.bmsConfigured);
  EXPECT_TRUE(st.bmsBusUp);
  EXPECT_EQ(st.bmsLastFrame, 0);
  EXPECT_TRUE(std::isnan(st.bmsLimits.cclA));
  r.bms.send(can::encode351(14.1, 55.0, 100.0, 12.0));
  r.svc.poll(fromSec(2.0));
  st = r.h.canStatus.load();
  EXPECT_EQ(st.now, fromSec(2.0));
  EXPECT_EQ(st.bmsLastFrame, fromSec(2.0));
  EXPECT_NEAR(st.bmsLimits.cclA, 55.0, 1e-9);
  EXPECT_EQ(st.bmsFrames, 1u);
  EXPECT_FALSE(st.n2kConfigured);
}

TEST(CanService, EveryReceivedFrameIsInTheCandumpLog) {
  ServiceRig r;
  r.logTime = 12.5;
  r.bms.send(can::encode351(14.1, 55.0, 100.0, 12.0));
  r.bms.send(can::encode355(80.0, 99.0));
  r.svc.poll(fromSec(1.0));
  std::istringstream in(r.log.str());
  std::string line;
  std::vector<can::CandumpLine> lines;
  while (std::getline(in, line)) {
    auto p = can::parseCandump(line);
    ASSERT_TRUE(p) << line;
    lines.push_back(*p);
  }
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].interface, "simcan0");
  EXPECT_DOUBLE_EQ(lines[0].timeSec, 12.5);
  EXPECT_EQ(lines[0].frame, can::encode351(14.1, 55.0, 100.0, 12.0));
  EXPECT_EQ(lines[1].frame, can::encode355(80.0, 99.0));
}

}  // namespace
}  // namespace xr::canlink
