// NMEA 2000: identifiers, fast packets both ways, NAME, the PGNs we send and
// the engine speed we read, and the address claim's conflict handling.
#include "can/n2k_codec.h"

#include <gtest/gtest.h>

#include <cmath>

#include "can/n2k_address.h"

namespace xr::can {
namespace {

TEST(N2kId, Pdu2AndPdu1RoundTrip) {
  N2kId id;
  id.priority = 2;
  id.pgn = 127488;
  id.source = 0x23;
  const std::uint32_t raw = encodeN2kId(id);
  EXPECT_EQ(raw, 0x09F20023u);  // 2 << 26 | 0x1F200 << 8 | 0x23
  const N2kId back = decodeN2kId(raw);
  EXPECT_EQ(back.pgn, 127488u);
  EXPECT_EQ(back.source, 0x23);
  EXPECT_EQ(back.priority, 2);
  N2kId claim;
  claim.pgn = 60928;
  claim.source = 35;
  claim.destination = 0xFF;
  EXPECT_EQ(encodeN2kId(claim), 0x18EEFF23u);  // priority 6, PF 0xEE, global destination
  EXPECT_EQ(decodeN2kId(0x18EEFF23u).pgn, 60928u);
  EXPECT_EQ(decodeN2kId(0x18EA2301u).pgn, 59904u);
  EXPECT_EQ(decodeN2kId(0x18EA2301u).destination, 0x23);
}

TEST(N2kFastPacket, ProductInformationSplitsAndReassembles) {
  const N2kMessage m = productInformation(35, 1234, "xregulator", "1.0", "A", "0001");
  ASSERT_EQ(m.data.size(), 134u);
  const auto frames = toFrames(m, 3);
  ASSERT_EQ(frames.size(), 20u);       // 6 + 19 x 7 >= 134
  EXPECT_EQ(frames[0].data[0], 0x60);  // sequence 3, frame 0
  EXPECT_EQ(frames[0].data[1], 134);
  EXPECT_EQ(frames[1].data[0], 0x61);
  const std::uint32_t fast[] = {126996, 127506};
  N2kAssembler a(fast);
  std::optional<N2kMessage> got;
  for (const auto& f : frames) {
    EXPECT_FALSE(got.has_value());
    got = a.feed(f);
  }
  ASSERT_TRUE(got);
  EXPECT_EQ(got->data, m.data);
  EXPECT_EQ(got->id.pgn, 126996u);
}

TEST(N2kFastPacket, AMissingFrameDropsTheMessage) {
  const auto frames = toFrames(dcDetailedStatus(35, 1, 0, N2kDcType::Battery, 80, 99), 0);
  ASSERT_EQ(frames.size(), 2u);  // 11 bytes: 6 + 5
  const std::uint32_t fast[] = {127506};
  N2kAssembler a(fast);
  CanFrame second = frames[1];
  EXPECT_FALSE(a.feed(second));  // no frame 0 seen
  EXPECT_FALSE(a.feed(frames[0]));
  const auto m = a.feed(frames[1]);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->data[3], 80);  // SoC
  EXPECT_EQ(m->data[2], 0);   // DC type battery
}

TEST(N2kName, FieldsRoundTrip) {
  N2kName n;
  n.uniqueNumber = 0x1ABCDE;
  n.manufacturerCode = 2046;
  n.deviceInstance = 0x25;
  n.deviceFunction = 140;
  n.deviceClass = 35;
  n.systemInstance = 3;
  n.industryGroup = 4;
  const std::uint64_t v = encodeName(n);
  const N2kName b = decodeName(v);
  EXPECT_EQ(b.uniqueNumber, n.uniqueNumber);
  EXPECT_EQ(b.manufacturerCode, n.manufacturerCode);
  EXPECT_EQ(b.deviceInstance, n.deviceInstance);
  EXPECT_EQ(b.deviceFunction, n.deviceFunction);
  EXPECT_EQ(b.deviceClass, n.deviceClass);
  EXPECT_EQ(b.systemInstance, n.systemInstance);
  EXPECT_EQ(b.industryGroup, 4);
  EXPECT_TRUE(b.arbitraryAddressCapable);
  EXPECT_EQ(v >> 60, 0xCu);  // arbitrary-address capable + marine industry group
}

TEST(N2kPgns, BatteryStatusAndDcVoltageCurrentScale) {
  const N2kMessage b = batteryStatus(35, 0, 13.57, -12.3, 25.0, 9);
  EXPECT_EQ(b.data[1] | b.data[2] << 8, 1357);
  EXPECT_EQ(static_cast<std::int16_t>(b.data[3] | b.data[4] << 8), -123);
  EXPECT_EQ(b.data[5] | b.data[6] << 8, 29815);  // 298.15 K
  const N2kMessage d = dcVoltageCurrent(35, 1, 1, 14.2, -1.5);
  EXPECT_EQ(d.data[2] | d.data[3] << 8, 142);
  const std::int32_t i = static_cast<std::int32_t>((d.data[4] | d.data[5] << 8 | d.data[6] << 16) << 8) >> 8;
  EXPECT_EQ(i, -150);
  EXPECT_EQ(converterStatus(35, 1, 1, N2kConverterState::Absorption).data[2], 4);
}

TEST(N2kEngine, RpmFrom127488And61444) {
  const auto r = decodeEngineSpeed(engineRapid(0, 0, 1800.25));
  ASSERT_TRUE(r);
  EXPECT_DOUBLE_EQ(r->rpm, 1800.25);
  N2kMessage na = engineRapid(0, 0, 0);
  na.data[1] = 0xFF;
  na.data[2] = 0xFF;
  EXPECT_FALSE(decodeEngineSpeed(na));
  N2kMessage eec1;
  eec1.id.pgn = 61444;
  eec1.data = {0xF0, 0x7D, 0x7D, 0x80, 0x38, 0x00, 0xF0, 0x7D};  // 0x3880 = 14464 x 0.125 = 1808 rpm
  const auto j = decodeEngineSpeed(eec1);
  ASSERT_TRUE(j);
  EXPECT_DOUBLE_EQ(j->rpm, 1808.0);
  N2kMessage other = batteryStatus(1, 0, 13, 0, 20, 0);
  EXPECT_FALSE(decodeEngineSpeed(other));
}

N2kMessage claimFrom(std::uint8_t source, std::uint32_t unique) {
  N2kName n;
  n.uniqueNumber = unique;
  n.manufacturerCode = 2046;
  return addressClaim(source, n);
}

TEST(N2kAddressClaim, SmallerNameKeepsTheAddress) {
  N2kName ours;
  ours.uniqueNumber = 500;
  ours.manufacturerCode = 2046;
  N2kAddressClaimer c(ours, 35);
  EXPECT_EQ(c.start().id.source, 35);
  // A node with a larger NAME claims 35: we keep it and claim again.
  auto answer = c.onMessage(claimFrom(35, 900));
  ASSERT_TRUE(answer);
  EXPECT_EQ(answer->id.source, 35);
  EXPECT_EQ(c.address(), 35);
  // A smaller NAME takes it: we move to 36 (37 is taken by a third node).
  c.onMessage(claimFrom(36, 100));  // 36 is someone else's
  answer = c.onMessage(claimFrom(35, 10));
  ASSERT_TRUE(answer);
  EXPECT_EQ(c.address(), 37);
  EXPECT_EQ(answer->id.source, 37);
  EXPECT_EQ(c.conflicts(), 2u);
  // A claim for another address needs no answer.
  EXPECT_FALSE(c.onMessage(claimFrom(50, 1)));
}

TEST(N2kAddressClaim, AnswersARequestForClaims) {
  N2kName ours;
  ours.uniqueNumber = 7;
  N2kAddressClaimer c(ours, 40);
  N2kMessage req;
  req.id.pgn = 59904;
  req.id.destination = 0xFF;
  req.data = {0x00, 0xEE, 0x00};  // 60928 little-endian
  const auto a = c.onMessage(req);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->id.pgn, 60928u);
  EXPECT_EQ(a->id.source, 40);
}

}  // namespace
}  // namespace xr::can
