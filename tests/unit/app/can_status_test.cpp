// /api/system's CAN words from the CAN service's status (docs/integrations.md): each
// state at its edge, unknown values left unknown.
#include "app/can_status.h"

#include <gtest/gtest.h>

#include <cmath>

#include "can/bms_codec.h"

namespace xr::app {
namespace {

TEST(CanStatus, NothingConfiguredIsOff) {
  const web::CanState c = canStateOf(rt::CanStatusHandoff{}, true);
  EXPECT_EQ(c.bms.state, "off");
  EXPECT_TRUE(c.bms.protocol.empty());
  EXPECT_TRUE(std::isnan(c.bms.cvl_v));
  EXPECT_EQ(c.n2k.state, "off");
  EXPECT_EQ(c.n2k.address, -1);
}

TEST(CanStatus, BmsStatesAtTheirEdges) {
  rt::CanStatusHandoff st;
  st.bmsConfigured = true;
  st.bmsProtocol = static_cast<std::uint8_t>(can::BmsProtocol::Rec);
  st.now = fromSec(100);
  EXPECT_EQ(canStateOf(st, true).bms.state, "bus_error");  // configured, not open
  EXPECT_EQ(canStateOf(st, true).bms.protocol, "rec");
  st.bmsBusUp = true;
  EXPECT_EQ(canStateOf(st, true).bms.state, "silent");  // open, never heard
  EXPECT_TRUE(std::isnan(canStateOf(st, true).bms.age_s));
  st.bmsLastFrame = fromSec(100) - fromSec(kBmsSilentS);
  EXPECT_EQ(canStateOf(st, true).bms.state, "talking");  // exactly 5 s: still talking
  st.bmsLastFrame -= 1;
  EXPECT_EQ(canStateOf(st, true).bms.state, "silent");
  st.bmsLimits.cvlV = 14.2;
  st.bmsLimits.cclA = 40;
  st.bmsLimits.stamp = fromSec(97.5);
  st.bmsBadFrames = 4;
  const auto b = canStateOf(st, true).bms;
  EXPECT_DOUBLE_EQ(b.cvl_v, 14.2);
  EXPECT_DOUBLE_EQ(b.ccl_a, 40);
  EXPECT_TRUE(std::isnan(b.soc_pct));  // never sent: unknown, not 0
  EXPECT_DOUBLE_EQ(b.age_s, 2.5);
  EXPECT_EQ(b.bad_frames, 4u);
}

TEST(CanStatus, N2kStates) {
  rt::CanStatusHandoff st;
  st.n2kConfigured = true;
  EXPECT_EQ(canStateOf(st, true).n2k.state, "bus_error");
  EXPECT_FALSE(canStateOf(st, true).n2k.claimed);
  st.n2kBusUp = true;
  EXPECT_EQ(canStateOf(st, true).n2k.state, "no_address");
  EXPECT_EQ(canStateOf(st, true).n2k.address, -1);
  st.n2kClaimed = true;
  st.n2kAddress = 36;
  st.n2kTxFrames = 10;
  const auto n = canStateOf(st, true).n2k;
  EXPECT_EQ(n.state, "claimed");
  EXPECT_TRUE(n.claimed);
  EXPECT_EQ(n.address, 36);
  EXPECT_EQ(n.tx_frames, 10u);
}

}  // namespace
}  // namespace xr::app
