#include "runtime/spsc_queue.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <thread>

namespace xr::rt {
namespace {

TEST(SpscQueue, PopsInPushOrder) {
  SpscQueue<int, 8> q;
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(q.push(i));
  EXPECT_EQ(q.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    int v = -1;
    ASSERT_TRUE(q.pop(v));
    EXPECT_EQ(v, i);
  }
  int v = 0;
  EXPECT_FALSE(q.pop(v));
  EXPECT_TRUE(q.empty());
}

TEST(SpscQueue, RejectsPushWhenFullAndKeepsContents) {
  SpscQueue<int, 4> q;
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(q.push(i));
  EXPECT_FALSE(q.push(99));
  int v = -1;
  ASSERT_TRUE(q.pop(v));
  EXPECT_EQ(v, 0);
  EXPECT_TRUE(q.push(4));  // room again after one pop
  for (int want = 1; want <= 4; ++want) {
    ASSERT_TRUE(q.pop(v));
    EXPECT_EQ(v, want);
  }
}

TEST(SpscQueue, WrapsAroundManyTimes) {
  SpscQueue<std::uint32_t, 4> q;
  std::uint32_t next = 0;
  for (std::uint32_t i = 0; i < 1000; ++i) {
    ASSERT_TRUE(q.push(i));
    if (i % 3 == 2) {
      std::uint32_t v;
      while (q.pop(v)) EXPECT_EQ(v, next++);
    }
  }
  std::uint32_t v;
  while (q.pop(v)) EXPECT_EQ(v, next++);
  EXPECT_EQ(next, 1000u);
}

// Two threads: every item arrives exactly once, in order (run under TSan by
// the runtime_tsan test).
TEST(SpscQueue, ConcurrentProducerConsumerLosesNothing) {
  SpscQueue<std::uint64_t, 64> q;
  constexpr std::uint64_t kItems = 200000;
  std::thread producer([&] {
    for (std::uint64_t i = 1; i <= kItems;) {
      if (q.push(i)) ++i;
      else std::this_thread::yield();
    }
  });
  std::uint64_t expected = 1;
  std::uint64_t sum = 0;
  while (expected <= kItems) {
    std::uint64_t v;
    if (q.pop(v)) {
      ASSERT_EQ(v, expected);
      sum += v;
      ++expected;
    } else {
      std::this_thread::yield();
    }
  }
  producer.join();
  EXPECT_EQ(sum, kItems * (kItems + 1) / 2);
}

}  // namespace
}  // namespace xr::rt
