#include "runtime/rt_setup.h"

#include <gtest/gtest.h>
#include <pthread.h>

#include <cstdio>
#include <fstream>
#include <thread>

namespace xr::rt {
namespace {

TEST(RtSetup, NamesTheThreadAndReportsEveryRefusal) {
  RtSetupReport r;
  std::thread t([&] {
    RuntimeSettings s;
    s.rt_priority = 80;
    s.cpu = 0;
    r = setupRealtimeThread(s, "xr-control-test", /*lockMemory=*/false);
    char name[16] = {};
    pthread_getname_np(pthread_self(), name, sizeof(name));
    EXPECT_STREQ(name, "xr-control-test");
  });
  t.join();
  EXPECT_TRUE(r.named);
  EXPECT_TRUE(r.stackPrefaulted);
  // Either granted, or refused with a warning that says so: never silent.
  if (!r.fifo) {
    bool mentioned = false;
    for (auto& w : r.warnings) mentioned |= w.find("SCHED_FIFO") != std::string::npos;
    EXPECT_TRUE(mentioned);
    EXPECT_NE(r.summary().find("normal scheduling"), std::string::npos);
  } else {
    EXPECT_EQ(r.priority, 80);
    EXPECT_NE(r.summary().find("SCHED_FIFO 80"), std::string::npos);
  }
}

// The simulator at --speed max: named and pre-faulted, but normal
// scheduling, and nothing refused because nothing was asked.
TEST(RtSetup, WithoutFifoTheThreadKeepsNormalScheduling) {
  RtSetupReport r;
  int policy = -1;
  std::thread t([&] {
    RuntimeSettings s;
    s.rt_priority = 80;
    r = setupRealtimeThread(s, "xr-control-test", /*lockMemory=*/false, /*fifo=*/false);
    sched_param sp{};
    pthread_getschedparam(pthread_self(), &policy, &sp);
  });
  t.join();
  EXPECT_TRUE(r.named);
  EXPECT_TRUE(r.stackPrefaulted);
  EXPECT_FALSE(r.fifo);
  EXPECT_FALSE(r.memoryLocked);
  EXPECT_EQ(policy, SCHED_OTHER);
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_NE(r.summary().find("normal scheduling"), std::string::npos);
}

TEST(RtSetup, DetectsPreemptRtFromTheSysfsFlag) {
  const std::string path = ::testing::TempDir() + "xr_realtime_flag";
  { std::ofstream(path) << "1\n"; }
  auto info = detectPreemptRt(path);
  EXPECT_TRUE(info.preemptRt);
  EXPECT_NE(info.how.find(path), std::string::npos);
  { std::ofstream(path) << "0\n"; }
  EXPECT_FALSE(detectPreemptRt(path).preemptRt);
  std::remove(path.c_str());
}

TEST(RtSetup, FallsBackToUnameWhenTheFlagIsAbsent) {
  auto info = detectPreemptRt("/nonexistent/realtime");
  EXPECT_FALSE(info.release.empty());
  EXPECT_FALSE(info.how.empty());
}

}  // namespace
}  // namespace xr::rt
