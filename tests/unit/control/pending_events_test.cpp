// PendingEvents on its own: command events wait for the next step in order;
// at capacity one more is refused (not an overwrite); a drain empties it.
#include "control/pending_events.h"

#include <gtest/gtest.h>

namespace xr {
namespace {

TEST(PendingEventsPart, HoldsUpToCapacityInOrderAndDrains) {
  PendingEvents q;
  for (std::size_t i = 0; i < PendingEvents::kCapacity; ++i)
    EXPECT_TRUE(q.queue(makeEvent(static_cast<TimeNs>(i), EventLevel::Info, EventCode::CommandApplied)));
  EXPECT_FALSE(q.queue(makeEvent(99, EventLevel::Info, EventCode::CommandApplied)));
  EventBatch ev;
  q.drainInto(ev);
  ASSERT_EQ(ev.count, PendingEvents::kCapacity);
  EXPECT_EQ(ev.items[0].t, 0);
  EXPECT_EQ(ev.items[PendingEvents::kCapacity - 1].t, static_cast<TimeNs>(PendingEvents::kCapacity - 1));
  EXPECT_EQ(q.size(), 0u);
  EventBatch again;
  q.drainInto(again);
  EXPECT_EQ(again.count, 0u);
}

}  // namespace
}  // namespace xr
