#include "runtime/triple_buffer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <thread>

#include "params/params.h"

namespace xr::rt {
namespace {

TEST(TripleBuffer, UpdateIsFalseUntilSomethingIsWritten) {
  Params initial;
  TripleBuffer<Params> tb(initial);
  EXPECT_FALSE(tb.update());
  EXPECT_EQ(tb.current(), initial);
}

TEST(TripleBuffer, ReaderGetsTheWholeNewestValueOnce) {
  TripleBuffer<Params> tb{Params{}};
  Params a;
  a.BulkVoltage = 14.2;
  Params b;
  b.BulkVoltage = 14.0;
  b.FloatVoltage = 13.2;
  tb.write(a);
  tb.write(b);  // newest wins: a is never seen
  ASSERT_TRUE(tb.update());
  EXPECT_EQ(tb.current(), b);
  EXPECT_FALSE(tb.update());
  EXPECT_EQ(tb.current(), b);  // stays valid
}

TEST(TripleBuffer, CurrentStaysStableWhileWriterKeepsWriting) {
  TripleBuffer<int> tb(0);
  tb.write(1);
  ASSERT_TRUE(tb.update());
  const int* held = &tb.current();
  for (int i = 2; i < 10; ++i) tb.write(i);
  EXPECT_EQ(*held, 1);  // the reader's slot is never written
  ASSERT_TRUE(tb.update());
  EXPECT_EQ(tb.current(), 9);
}

struct Pair {
  std::uint64_t a = 0;
  std::uint64_t filler[64] = {};
  std::uint64_t b = 0;
};

TEST(TripleBuffer, ConcurrentSwapIsNeverTornAndMonotonic) {
  TripleBuffer<Pair> tb{Pair{}};
  std::atomic<bool> done{false};
  constexpr std::uint64_t kWrites = 50000;
  std::thread writer([&] {
    Pair p;
    for (std::uint64_t i = 1; i <= kWrites; ++i) {
      p.a = i;
      p.b = i * 3;
      tb.write(p);
    }
    done = true;
  });
  std::uint64_t last = 0, torn = 0, backwards = 0;
  while (!done.load()) {
    if (tb.update()) {
      const Pair& p = tb.current();
      if (p.b != p.a * 3) ++torn;
      if (p.a < last) ++backwards;
      last = p.a;
    }
  }
  writer.join();
  tb.update();
  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(backwards, 0u);
  EXPECT_EQ(tb.current().a, kWrites);
}

}  // namespace
}  // namespace xr::rt
