// The boat's position on NMEA 2000 (129025, 129029): both ways, through the
// fast-packet assembler, and every "cannot know" a receiver may send.
#include "can/n2k_position.h"

#include <gtest/gtest.h>

#include "can/can_bytes.h"

namespace xr::can {
namespace {

TEST(N2kPosition, RapidUpdateRoundTripsAt1e7Degrees) {
  const auto p = decodePosition(positionRapid(7, 43.2965432, -5.3698765));
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->latitudeDeg, 43.2965432, 1e-7);
  EXPECT_NEAR(p->longitudeDeg, -5.3698765, 1e-7);
  EXPECT_EQ(positionRapid(7, 1, 1).id.pgn, 129025u);
  EXPECT_EQ(positionRapid(7, 1, 1).data.size(), 8u);
}

TEST(N2kPosition, GnssPositionGoesAsFastPacketAndReassembles) {
  const N2kMessage m = gnssPosition(9, 3, -33.8567844, 151.2152967);
  EXPECT_EQ(m.data.size(), 43u);
  const std::uint32_t fast[] = {129029};
  N2kAssembler a(fast);
  std::optional<N2kMessage> whole;
  const auto frames = toFrames(m, 2);
  EXPECT_EQ(frames.size(), 7u);  // 6 + 6 * 7 >= 43
  for (const CanFrame& f : frames)
    if (auto got = a.feed(f)) whole = got;
  ASSERT_TRUE(whole);
  const auto p = decodePosition(*whole);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->latitudeDeg, -33.8567844, 1e-9);
  EXPECT_NEAR(p->longitudeDeg, 151.2152967, 1e-9);
}

TEST(N2kPosition, NotAvailableFieldsAreNoPosition) {
  N2kMessage r = positionRapid(7, 10, 20);
  putS32(r.data, 0, 0x7FFFFFFF);  // latitude "not available"
  EXPECT_FALSE(decodePosition(r));
  N2kMessage g = gnssPosition(7, 0, 10, 20);
  putS64(g.data, 15, 0x7FFFFFFFFFFFFFFFLL);  // longitude "not available"
  EXPECT_FALSE(decodePosition(g));
}

TEST(N2kPosition, NoFixOrSimulatedMethodIsNoPosition) {
  EXPECT_FALSE(decodePosition(gnssPosition(7, 0, 10, 20, 0)));  // no GNSS
  EXPECT_FALSE(decodePosition(gnssPosition(7, 0, 10, 20, 8)));  // simulate mode
  EXPECT_TRUE(decodePosition(gnssPosition(7, 0, 10, 20, 2)));   // DGNSS fix
  EXPECT_TRUE(decodePosition(gnssPosition(7, 0, 10, 20, 7)));   // manual input
}

TEST(N2kPosition, OutOfRangeShortOrOtherPgnIsNoPosition) {
  EXPECT_FALSE(decodePosition(positionRapid(7, 90.5, 0)));
  EXPECT_FALSE(decodePosition(positionRapid(7, 0, -180.5)));
  EXPECT_TRUE(decodePosition(positionRapid(7, 90.0, -180.0)));
  N2kMessage shortRapid = positionRapid(7, 10, 20);
  shortRapid.data.resize(7);
  EXPECT_FALSE(decodePosition(shortRapid));
  N2kMessage shortGnss = gnssPosition(7, 0, 10, 20);
  shortGnss.data.resize(31);
  EXPECT_FALSE(decodePosition(shortGnss));
  N2kMessage other = positionRapid(7, 10, 20);
  other.id.pgn = 127488;
  EXPECT_FALSE(decodePosition(other));
}

}  // namespace
}  // namespace xr::can
