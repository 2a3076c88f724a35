// The simulated segment: every other node hears a frame, the sender does not.
#include "drivers/can/sim_can_bus.h"

#include <gtest/gtest.h>

namespace xr::can {
namespace {

TEST(SimCanSegment, OthersHearTheSenderDoesNot) {
  SimCanSegment seg;
  SimCanNode& a = seg.attach();
  SimCanNode& b = seg.attach();
  SimCanNode& c = seg.attach();
  CanFrame f;
  f.id = 0x351;
  f.dlc = 1;
  f.data[0] = 7;
  ASSERT_TRUE(a.send(f));
  EXPECT_FALSE(a.receive(std::chrono::milliseconds(0)));
  auto rb = b.receive(std::chrono::milliseconds(0));
  auto rc = c.receive(std::chrono::milliseconds(0));
  ASSERT_TRUE(rb && rc);
  EXPECT_EQ(*rb, f);
  EXPECT_EQ(*rc, f);
  EXPECT_FALSE(b.receive(std::chrono::milliseconds(0)));
  EXPECT_EQ(a.stats().tx, 1u);
  EXPECT_EQ(b.stats().rx, 1u);
}

TEST(SimCanSegment, ASilentNodeReachesNobodyAndErrorFramesCount) {
  SimCanSegment seg;
  SimCanNode& a = seg.attach();
  SimCanNode& b = seg.attach();
  a.setSilent(true);
  CanFrame f;
  f.id = 0x351;
  a.send(f);
  EXPECT_FALSE(b.receive(std::chrono::milliseconds(0)));
  a.setSilent(false);
  f.error = true;
  a.send(f);
  ASSERT_TRUE(b.receive(std::chrono::milliseconds(0)));
  EXPECT_EQ(b.stats().errorFrames, 1u);
}

}  // namespace
}  // namespace xr::can
