// Our NMEA 2000 node (docs/integrations.md): claims its address first, answers requests,
// publishes on the bus from the telemetry snapshot at its rates, and moves
// when a node with a smaller NAME claims its address.
#include "canlink/n2k_node.h"

#include <gtest/gtest.h>

#include <vector>

#include "drivers/can/sim_can_bus.h"

namespace xr::canlink {
namespace {

struct NodeRig {
  can::SimCanSegment seg;
  can::SimCanNode& other = seg.attach();  // another device on the backbone
  can::SimCanNode& ours = seg.attach();
  rt::Handoffs h{Params{}};
  N2kNode node{ours, 35, h, "1.2.3"};
  can::N2kAssembler assembler{std::vector<std::uint32_t>{126996, 127506}};

  std::vector<can::N2kMessage> heard() {
    std::vector<can::N2kMessage> out;
    while (auto f = other.receive(std::chrono::milliseconds(0)))
      if (auto m = assembler.feed(*f)) out.push_back(*m);
    return out;
  }
  void publishTelemetry(double v, double bcur, double alt, double soc) {
    rt::RuntimeSnapshot s;
    s.tick = 1;
    s.telemetry.battery_v = v;
    s.telemetry.bcur_a = bcur;
    s.telemetry.alt_a = alt;
    s.telemetry.soc_pct = soc;
    s.telemetry.battery.socSource = SocSource::Counted;  // the shown SoC is the counted one
    s.telemetry.mode = FieldControlMode::MODE_NORMAL_AUTO_PID;
    s.telemetry.stage = ChargeStage::ABSORPTION;
    s.telemetry.field_enable = true;
    h.snapshot.store(s);
  }
  static int count(const std::vector<can::N2kMessage>& ms, std::uint32_t pgn) {
    int n = 0;
    for (const auto& m : ms) n += m.id.pgn == pgn;
    return n;
  }
};

TEST(N2kNode, ClaimsFirstAndSendsNothingElseFor250Ms) {
  NodeRig r;
  r.publishTelemetry(13.8, 20.0, 30.0, 80.0);
  r.node.poll(fromSec(1.0));
  auto ms = r.heard();
  ASSERT_EQ(ms.size(), 1u);
  EXPECT_EQ(ms[0].id.pgn, 60928u);
  EXPECT_EQ(ms[0].id.source, 35);
  r.node.poll(fromSec(1.249));
  EXPECT_TRUE(r.heard().empty());
  r.node.poll(fromSec(1.25));
  ms = r.heard();
  EXPECT_EQ(NodeRig::count(ms, 126993), 1);
  for (std::uint32_t pgn : {127506u, 127508u, 127750u, 127751u}) EXPECT_EQ(NodeRig::count(ms, pgn), 1) << pgn;
}

TEST(N2kNode, PublishesAtItsRatesFromTheTelemetry) {
  NodeRig r;
  r.publishTelemetry(13.84, -4.5, 31.25, 77.0);
  std::vector<can::N2kMessage> all;
  for (TimeNs t = 0; t <= fromSec(121.0); t += fromMs(10)) {
    r.node.poll(t);
    for (auto& m : r.heard()) all.push_back(m);
  }
  // Heartbeat at 0.25 s, 60.25 s, 120.25 s; status every 1.5 s from 0.25 s.
  EXPECT_EQ(NodeRig::count(all, 126993), 3);
  EXPECT_EQ(NodeRig::count(all, 127508), 81);
  for (const auto& m : all) {
    if (m.id.pgn == 127508) {
      EXPECT_EQ(m.data[0], 0);                                                 // instance
      EXPECT_EQ(static_cast<std::int16_t>(m.data[1] | m.data[2] << 8), 1384);  // 0.01 V
      EXPECT_EQ(static_cast<std::int16_t>(m.data[3] | m.data[4] << 8), -45);   // 0.1 A
    } else if (m.id.pgn == 127750) {
      EXPECT_EQ(m.data[2], static_cast<std::uint8_t>(can::N2kConverterState::Absorption));
    } else if (m.id.pgn == 127506) {
      EXPECT_EQ(m.data[3], 77);
    }
  }
}

// One SoC on every screen: while the SoC is not known (no BMS, not yet counted), the
// bus says "not available" rather than a number a chart plotter would show.
TEST(N2kNode, AnUnknownSocIsNotAvailableOnTheBus) {
  NodeRig r;
  r.publishTelemetry(12.9, 0.0, 0.0, 55.0);
  rt::RuntimeSnapshot s = r.h.snapshot.load();
  s.telemetry.battery.socSource = SocSource::Unknown;
  r.h.snapshot.store(s);
  std::vector<can::N2kMessage> all;
  for (TimeNs t = 0; t <= fromSec(3.0); t += fromMs(10)) {
    r.node.poll(t);
    for (auto& m : r.heard()) all.push_back(m);
  }
  ASSERT_GE(NodeRig::count(all, 127506), 1);
  for (const auto& m : all)
    if (m.id.pgn == 127506) {
      EXPECT_EQ(m.data[3], 0xFF);
    }
}

TEST(N2kNode, NoStatusBeforeTheFirstTelemetry) {
  NodeRig r;
  r.node.poll(0);
  r.node.poll(fromSec(1.0));
  const auto ms = r.heard();
  EXPECT_EQ(NodeRig::count(ms, 127508), 0);
  EXPECT_EQ(NodeRig::count(ms, 126993), 1);  // the heartbeat says we are alive
}

TEST(N2kNode, AnswersARequestForProductInformation) {
  NodeRig r;
  r.node.poll(0);
  r.heard();
  can::N2kMessage req;
  req.id.pgn = 59904;
  req.id.source = 10;
  req.id.destination = 35;
  req.data = {0x14, 0xF0, 0x01};  // 126996 = 0x1F014, little-endian
  for (const auto& f : can::toFrames(req, 0)) r.other.send(f);
  r.node.poll(fromMs(100));
  const auto ms = r.heard();
  ASSERT_EQ(NodeRig::count(ms, 126996), 1);
  for (const auto& m : ms)
    if (m.id.pgn == 126996) {
      ASSERT_EQ(m.data.size(), 134u);
      EXPECT_EQ(std::string(m.data.begin() + 4, m.data.begin() + 14), "xregulator");
      EXPECT_EQ(std::string(m.data.begin() + 68, m.data.begin() + 73), "1.2.3");
    }
  // A request for someone else's product information is not ours to answer.
  req.id.destination = 36;
  for (const auto& f : can::toFrames(req, 0)) r.other.send(f);
  r.node.poll(fromMs(200));
  EXPECT_EQ(NodeRig::count(r.heard(), 126996), 0);
}

TEST(N2kNode, MovesWhenASmallerNameClaimsItsAddress) {
  NodeRig r;
  r.node.poll(0);
  r.heard();
  can::N2kName smaller;  // all zero but the industry group: smaller than ours
  for (const auto& f : can::toFrames(can::addressClaim(35, smaller), 0)) r.other.send(f);
  r.node.poll(fromMs(10));
  const auto ms = r.heard();
  ASSERT_EQ(NodeRig::count(ms, 60928), 1);
  EXPECT_NE(r.node.address(), 35);
  for (const auto& m : ms)
    if (m.id.pgn == 60928) {
      EXPECT_EQ(m.id.source, r.node.address());
    }
}

TEST(N2kNode, OperatingStateFollowsModeFieldAndStage) {
  Telemetry t;
  t.mode = FieldControlMode::MODE_NORMAL_AUTO_PID;
  t.field_enable = true;
  t.stage = ChargeStage::FLOAT;
  EXPECT_EQ(converterStateOf(t), can::N2kConverterState::Float);
  t.stage = ChargeStage::BULK;
  EXPECT_EQ(converterStateOf(t), can::N2kConverterState::Bulk);
  t.field_enable = false;
  EXPECT_EQ(converterStateOf(t), can::N2kConverterState::Off);
  t.mode = FieldControlMode::MODE_CRITICAL_RAMP;
  EXPECT_EQ(converterStateOf(t), can::N2kConverterState::Fault);
  t.mode = FieldControlMode::MODE_DISABLED_RAMP;
  t.field_enable = true;
  EXPECT_EQ(converterStateOf(t), can::N2kConverterState::Off);
}

}  // namespace
}  // namespace xr::canlink
