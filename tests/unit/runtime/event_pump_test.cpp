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

namespace xr::rt {
namespace {

// Events of the non-RT threads (side_events.h): bounded, drops counted,
// delivered by the pump with the ring's.
TEST(SideEvents, BoundedAndDropsAreCounted) {
  SideEvents q;
  for (std::size_t i = 0; i < SideEvents::kCapacity; ++i) {
    Event e;
    e.a = static_cast<double>(i);
    EXPECT_TRUE(q.post(e));
  }
  EXPECT_FALSE(q.post(Event{}));  // full: the newest is lost, not waited for
  EXPECT_FALSE(q.post(Event{}));
  EXPECT_EQ(q.dropped(), 2u);
  std::array<Event, SideEvents::kCapacity> out;
  ASSERT_EQ(q.take(out), SideEvents::kCapacity);
  for (std::size_t i = 0; i < SideEvents::kCapacity; ++i) EXPECT_EQ(out[i].a, static_cast<double>(i));
  EXPECT_EQ(q.take(out), 0u);
  EXPECT_TRUE(q.post(Event{}));  // room again, and the ring index wrapped
  EXPECT_EQ(q.take(out), 1u);
  EXPECT_EQ(q.dropped(), 2u);
}

TEST(SideEvents, ThePumpDeliversThemWithTheRingsEvents) {
  EventRing ring;
  SideEvents side;
  EventPump pump(ring);
  pump.addSource(side);
  std::vector<int> seen;
  pump.addSink([&](const Event& e) { seen.push_back(e.detail); });
  Event rt;
  rt.detail = 1;
  ring.push(rt);
  Event can;
  can.detail = 2;
  side.post(can);
  EXPECT_EQ(pump.drainOnce(), 2u);
  EXPECT_EQ(seen, (std::vector<int>{1, 2}));
  EXPECT_EQ(pump.delivered(), 2u);
}

// Several producer threads against the pump (TSan target).
TEST(SideEvents, ConcurrentProducersAndThePump) {
  EventRing ring;
  SideEvents side;
  EventPump pump(ring, std::chrono::milliseconds(1));
  pump.addSource(side);
  std::atomic<int> seen{0};
  pump.addSink([&](const Event&) { ++seen; });
  pump.start();
  std::atomic<int> posted{0};
  std::vector<std::thread> producers;
  for (int t = 0; t < 3; ++t)
    producers.emplace_back([&] {
      for (int i = 0; i < 300; ++i) posted += side.post(Event{}) ? 1 : 0;
    });
  for (auto& p : producers) p.join();
  pump.stop();
  EXPECT_EQ(seen.load(), posted.load());
  EXPECT_EQ(static_cast<std::uint64_t>(posted.load()) + side.dropped(), 900u);
}

}  // namespace
}  // namespace xr::rt
