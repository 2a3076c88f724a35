// candump log lines: what we write is what candump/canplayer write, and reads back.
#include "drivers/can/candump_log.h"

#include <gtest/gtest.h>

namespace xr::can {
namespace {

TEST(Candump, FormatsStandardExtendedAndErrorFrames) {
  CanFrame s;
  s.id = 0x351;
  s.dlc = 8;
  s.data = {0x8C, 0x00, 0xF4, 0x01, 0xF4, 0x01, 0x00, 0x00};
  EXPECT_EQ(formatCandump(1700000000.0, "can0", s), "(1700000000.000000) can0 351#8C00F401F4010000");
  CanFrame e;
  e.id = 0x09F20123;
  e.extended = true;
  e.dlc = 2;
  e.data[0] = 0xAB;
  e.data[1] = 0x01;
  EXPECT_EQ(formatCandump(1.5, "can1", e), "(1.500000) can1 09F20123#AB01");
  CanFrame err;
  err.error = true;
  err.id = 0x40;  // CAN_ERR_BUSOFF
  err.dlc = 8;
  EXPECT_EQ(formatCandump(2, "can0", err), "(2.000000) can0 20000040#0000000000000000");
}

TEST(Candump, ParsesWhatItFormats) {
  CanFrame f;
  f.id = 0x1CF00400;
  f.extended = true;
  f.dlc = 8;
  f.data = {1, 2, 3, 4, 5, 6, 7, 8};
  const auto l = parseCandump(formatCandump(12.25, "vcan0", f) + "\n");
  ASSERT_TRUE(l);
  EXPECT_EQ(l->frame, f);
  EXPECT_EQ(l->interface, "vcan0");
  EXPECT_DOUBLE_EQ(l->timeSec, 12.25);
  const auto err = parseCandump("(2.000000) can0 20000040#0000000000000000");
  ASSERT_TRUE(err);
  EXPECT_TRUE(err->frame.error);
  EXPECT_EQ(err->frame.id, 0x40u);
  const auto empty = parseCandump("(3.0) can0 35E#");
  ASSERT_TRUE(empty);
  EXPECT_EQ(empty->frame.dlc, 0);
}

TEST(Candump, RejectsMalformedLines) {
  EXPECT_FALSE(parseCandump(""));
  EXPECT_FALSE(parseCandump("351#00"));
  EXPECT_FALSE(parseCandump("(x) can0 351#00"));
  EXPECT_FALSE(parseCandump("(1.0) can0 3510#00"));                 // 4 hex digits: neither form
  EXPECT_FALSE(parseCandump("(1.0) can0 351#0"));                   // odd number of hex digits
  EXPECT_FALSE(parseCandump("(1.0) can0 351#001122334455667788"));  // 9 bytes
  EXPECT_FALSE(parseCandump("(1.0) can0 351#ZZ"));
  EXPECT_FALSE(parseCandump("(1.0) can0 FFF0#00"));
  EXPECT_FALSE(parseCandump("(1.0) can0 9FF#00"));  // > 0x7FF in the 11-bit form
}

}  // namespace
}  // namespace xr::can
