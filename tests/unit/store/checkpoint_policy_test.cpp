#include "store/checkpoint_policy.h"

#include <gtest/gtest.h>

namespace xr {
namespace {

constexpr TimeNs S = 1'000'000'000;
// A wall clock (UTC ms) that runs with the monotonic one.
std::int64_t wall(TimeNs t) { return t / 1'000'000; }

TEST(CheckpointPolicy, EveryIntervalOnTheWallClocksMarks) {
  CheckpointPolicy p(300);
  const TimeNs t = 1000 * S;  // 16:40 past the epoch: the next marks are 1200 s, 1500 s, ...
  EXPECT_EQ(p.poll(t, wall(t), true, ChargeStage::BULK, false), CheckpointReason::None);
  int count = 0;
  TimeNs first = -1;
  for (int i = 1; i <= 3600; ++i)
    if (p.poll(t + i * S, wall(t + i * S), true, ChargeStage::BULK, false) == CheckpointReason::Interval) {
      ++count;
      if (first < 0) first = t + i * S;
    }
  EXPECT_EQ(count, 12);
  EXPECT_EQ(first, 1200 * S);  // on the mark, not 300 s after the start
  EXPECT_EQ(p.poll(t + 3799 * S, wall(t + 3799 * S), true, ChargeStage::BULK, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(t + 3800 * S, wall(t + 3800 * S), true, ChargeStage::BULK, false),
            CheckpointReason::Interval);
}

TEST(CheckpointPolicy, AWallClockThatStandsStillStillSavesAfterAnIntervalAndAMinute) {
  CheckpointPolicy p(300);
  const std::int64_t stuck = 1'700'000'000'000;
  p.poll(0, stuck, true, ChargeStage::BULK, false);
  EXPECT_EQ(p.poll(359 * S, stuck, true, ChargeStage::BULK, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(360 * S, stuck, true, ChargeStage::BULK, false), CheckpointReason::Interval);
  EXPECT_EQ(p.poll(361 * S, stuck, true, ChargeStage::BULK, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(720 * S, stuck, true, ChargeStage::BULK, false), CheckpointReason::Interval);
}

TEST(CheckpointPolicy, FieldOffEdgePlusFiveSeconds) {
  CheckpointPolicy p(300);
  TimeNs t = 0;
  p.poll(t, wall(t), true, ChargeStage::BULK, false);
  t += 10 * S;
  EXPECT_EQ(p.poll(t, wall(t), false, ChargeStage::BULK, false), CheckpointReason::None);  // the edge
  EXPECT_EQ(p.poll(t + 4 * S, wall(t + 4 * S), false, ChargeStage::BULK, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(t + 5 * S, wall(t + 5 * S), false, ChargeStage::BULK, false), CheckpointReason::FieldOff);
  EXPECT_EQ(p.poll(t + 6 * S, wall(t + 6 * S), false, ChargeStage::BULK, false),
            CheckpointReason::None);  // once
}

TEST(CheckpointPolicy, FieldBackOnCancelsPendingFieldOff) {
  CheckpointPolicy p(300);
  p.poll(0, wall(0), true, ChargeStage::BULK, false);
  p.poll(1 * S, wall(1 * S), false, ChargeStage::BULK, false);
  EXPECT_EQ(p.poll(3 * S, wall(3 * S), true, ChargeStage::BULK, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(7 * S, wall(7 * S), true, ChargeStage::BULK, false), CheckpointReason::None);
}

TEST(CheckpointPolicy, StageTransitionAndStop) {
  CheckpointPolicy p(300);
  p.poll(0, wall(0), true, ChargeStage::BULK, false);
  EXPECT_EQ(p.poll(1 * S, wall(1 * S), true, ChargeStage::ABSORPTION, false), CheckpointReason::Stage);
  EXPECT_EQ(p.poll(2 * S, wall(2 * S), true, ChargeStage::ABSORPTION, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(3 * S, wall(3 * S), true, ChargeStage::ABSORPTION, true), CheckpointReason::Stop);
  EXPECT_EQ(p.poll(4 * S, wall(4 * S), false, ChargeStage::FLOAT, true), CheckpointReason::None);  // stopped
  EXPECT_EQ(toString(CheckpointReason::FieldOff), "field_off");
}

TEST(CheckpointPolicy, StageCheckpointRestartsTheStandingClocksNet) {
  CheckpointPolicy p(300);
  const std::int64_t stuck = 1'700'000'000'000;
  p.poll(0, stuck, true, ChargeStage::BULK, false);
  EXPECT_EQ(p.poll(200 * S, stuck, true, ChargeStage::FLOAT, false), CheckpointReason::Stage);
  EXPECT_EQ(p.poll(360 * S, stuck, true, ChargeStage::FLOAT, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(560 * S, stuck, true, ChargeStage::FLOAT, false), CheckpointReason::Interval);
}

TEST(CheckpointPolicy, AStageCheckpointDoesNotMoveTheWallClocksMarks) {
  CheckpointPolicy p(300);
  p.poll(0, wall(0), true, ChargeStage::BULK, false);
  EXPECT_EQ(p.poll(200 * S, wall(200 * S), true, ChargeStage::FLOAT, false), CheckpointReason::Stage);
  EXPECT_EQ(p.poll(299 * S, wall(299 * S), true, ChargeStage::FLOAT, false), CheckpointReason::None);
  EXPECT_EQ(p.poll(300 * S, wall(300 * S), true, ChargeStage::FLOAT, false), CheckpointReason::Interval);
}

}  // namespace
}  // namespace xr
