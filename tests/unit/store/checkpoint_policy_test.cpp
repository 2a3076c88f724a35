#include "store/checkpoint_policy.h"

#include <gtest/gtest.h>

namespace xr {
namespace {

constexpr TimeNs S = 1'000'000'000;

TEST(CheckpointPolicy, EveryInterval) {
  CheckpointPolicy p(300);
  TimeNs t = 1000 * S;
  EXPECT_EQ(p.poll(t, true, ChargeStage::BULK, false), CheckpointReason::None);
  int count = 0;
  for (int i = 1; i <= 3600; ++i)
    if (p.poll(t + i * S, true, ChargeStage::BULK, false) == CheckpointReason::Interval) ++count;
  EXPECT_EQ(count, 12);
  EXPECT_EQ(p.poll(t + 3899 * S, true, ChargeStage::BULK, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(t + 3900 * S, true, ChargeStage::BULK, false), CheckpointReason::Interval);
}

TEST(CheckpointPolicy, FieldOffEdgePlusFiveSeconds) {
  CheckpointPolicy p(300);
  TimeNs t = 0;
  p.poll(t, true, ChargeStage::BULK, false);
  t += 10 * S;
  EXPECT_EQ(p.poll(t, false, ChargeStage::BULK, false), CheckpointReason::None);  // the edge
  EXPECT_EQ(p.poll(t + 4 * S, false, ChargeStage::BULK, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(t + 5 * S, false, ChargeStage::BULK, false), CheckpointReason::FieldOff);
  EXPECT_EQ(p.poll(t + 6 * S, false, ChargeStage::BULK, false), CheckpointReason::None);  // once
}

TEST(CheckpointPolicy, FieldBackOnCancelsPendingFieldOff) {
  CheckpointPolicy p(300);
  p.poll(0, true, ChargeStage::BULK, false);
  p.poll(1 * S, false, ChargeStage::BULK, false);
  EXPECT_EQ(p.poll(3 * S, true, ChargeStage::BULK, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(7 * S, true, ChargeStage::BULK, false), CheckpointReason::None);
}

TEST(CheckpointPolicy, StageTransitionAndStop) {
  CheckpointPolicy p(300);
  p.poll(0, true, ChargeStage::BULK, false);
  EXPECT_EQ(p.poll(1 * S, true, ChargeStage::ABSORPTION, false), CheckpointReason::Stage);
  EXPECT_EQ(p.poll(2 * S, true, ChargeStage::ABSORPTION, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(3 * S, true, ChargeStage::ABSORPTION, true), CheckpointReason::Stop);
  EXPECT_EQ(p.poll(4 * S, false, ChargeStage::FLOAT, true), CheckpointReason::None);  // stopped
  EXPECT_EQ(toString(CheckpointReason::FieldOff), "field_off");
}

TEST(CheckpointPolicy, StageCheckpointRestartsInterval) {
  CheckpointPolicy p(300);
  p.poll(0, true, ChargeStage::BULK, false);
  EXPECT_EQ(p.poll(200 * S, true, ChargeStage::FLOAT, false), CheckpointReason::Stage);
  EXPECT_EQ(p.poll(300 * S, true, ChargeStage::FLOAT, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(500 * S, true, ChargeStage::FLOAT, false), CheckpointReason::Interval);
}

}  // namespace
}  // namespace xr
