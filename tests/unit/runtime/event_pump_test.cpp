#include "runtime/event_pump.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

namespace xr::rt {
namespace {

TEST(EventPump, DeliversEveryEventToEverySinkInOrder) {
  EventRing ring;
  EventPump pump(ring, std::chrono::milliseconds(1));
  std::mutex m;
  std::vector<double> a;
  std::atomic<int> b{0};
  pump.addSink([&](const Event& e) {
    std::lock_guard lock(m);
    a.push_back(e.a);
  });
  pump.addSink([&](const Event&) { ++b; });
  pump.start();
  for (int i = 0; i < 500; ++i) {
    Event e;
    e.a = i;
    while (!ring.push(e)) std::this_thread::yield();
  }
  pump.stop();  // drains the rest
  ASSERT_EQ(a.size(), 500u);
  for (int i = 0; i < 500; ++i) EXPECT_EQ(a[i], i);
  EXPECT_EQ(b.load(), 500);
  EXPECT_EQ(pump.delivered(), 500u);
}

TEST(EventPump, AThrowingSinkDoesNotStopTheOthers) {
  EventRing ring;
  EventPump pump(ring);
  int seen = 0;
  pump.addSink([](const Event&) { throw std::runtime_error("store gone"); });
  pump.addSink([&](const Event&) { ++seen; });
  ring.push(Event{});
  ring.push(Event{});
  EXPECT_EQ(pump.drainOnce(), 2u);
  EXPECT_EQ(seen, 2);
}

TEST(EventRing, BatchOverflowAndCoreDropsAreCounted) {
  EventRing ring;
  EventBatch b;
  for (std::size_t i = 0; i < EventBatch::kCapacity + 3; ++i) b.push(Event{});
  EXPECT_EQ(b.dropped, 3u);
  ring.pushBatch(b);
  EXPECT_EQ(ring.dropped(), 3u);
}

// RT producer batches while the pump consumes concurrently (TSan target).
TEST(EventPump, ConcurrentBatchesFromAnRtThread) {
  EventRing ring;
  EventPump pump(ring, std::chrono::milliseconds(1));
  std::atomic<int> seen{0};
  pump.addSink([&](const Event&) { ++seen; });
  pump.start();
  std::thread rt([&] {
    for (int tick = 0; tick < 2000; ++tick) {
      EventBatch b;
      b.push(Event{});
      b.push(Event{});
      ring.pushBatch(b);
      if (tick % 100 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  });
  rt.join();
  pump.stop();
  EXPECT_EQ(static_cast<std::uint64_t>(seen.load()) + ring.dropped(), 4000u);
}

}  // namespace
}  // namespace xr::rt
