// The integrations wait on the one clock (integrations/clock_wait.h,
// docs/architecture.md "One clock"): in simulation a minute of refresh is a
// minute of simulated time, whatever the wall clock did meanwhile.
#include "integrations/clock_wait.h"

#include <gtest/gtest.h>

#include <boost/asio/co_spawn.hpp>
#include <boost/asio/detached.hpp>
#include <boost/asio/io_context.hpp>
#include <chrono>

namespace xr::integrations {
namespace {
using namespace std::chrono_literals;
using Steady = std::chrono::steady_clock;

// A simulation at 600 x real time: its elapsed time from the wall's.
rt::WallClock fastSimulation(Steady::time_point start) {
  rt::WallClock c;
  c.followSimulation(
      [start] { return static_cast<TimeNs>(std::chrono::nanoseconds(Steady::now() - start).count() * 600); },
      600.0);
  return c;
}

TEST(ClockWait, AMinuteOfSimulatedTimeIsWaitedOnTheSimulatedClock) {
  const auto start = Steady::now();
  const rt::WallClock clock = fastSimulation(start);
  boost::asio::io_context io;
  const bool stopping = false;
  Steady::time_point simAtEnd{};
  boost::asio::co_spawn(
      io,
      [&]() -> boost::asio::awaitable<void> {
        const auto from = clock.steadyNow();
        co_await waitOnClock(clock, 60s, stopping);
        simAtEnd = clock.steadyNow() - (from - Steady::time_point{});
      },
      boost::asio::detached);
  io.run_for(30s);  // the wall clock would need 60 s
  EXPECT_GE(simAtEnd - Steady::time_point{}, 60s) << "never ends before the minute has passed on the clock";
  EXPECT_LT(Steady::now() - start, 30s) << "the wall clock's minute was not waited for";
}

TEST(ClockWait, AfterOnClockCallsOnceTheDurationHasPassedAndNeverWhenCancelled) {
  const rt::WallClock clock = fastSimulation(Steady::now());
  boost::asio::io_context io;
  boost::asio::steady_timer timer(io), cancelled(io);
  auto from = clock.steadyNow();
  Steady::duration waited{};
  bool cancelledCalled = false;
  afterOnClock(clock, timer, 30s, [&] { waited = clock.steadyNow() - from; });
  afterOnClock(clock, cancelled, 30s, [&] { cancelledCalled = true; });
  cancelled.cancel();
  io.run_for(20s);
  EXPECT_GE(waited, 30s);
  EXPECT_FALSE(cancelledCalled);
}

TEST(ClockWait, ARealTimerAsksTheClockAgainAtLeastOnceASecond) {
  const rt::WallClock board;
  EXPECT_FALSE(board.simulated());
  EXPECT_EQ(board.realWait(300ms), Steady::duration(300ms));
  EXPECT_EQ(board.realWait(7s), Steady::duration(1s)) << "a stop is seen within a second";
  const rt::WallClock sim = fastSimulation(Steady::now());
  // In simulation a real timer waits the simulated time at speed, and never
  // long: the clock is asked again (a loop slower than its speed is waited for).
  EXPECT_EQ(sim.realWait(60ms), Steady::duration(100us));
  EXPECT_EQ(sim.realWait(1h), Steady::duration(200ms));
}

TEST(ClockWait, AStopEndsAnHourLongWaitWithinASecond) {
  const auto start = Steady::now();
  const rt::WallClock board;
  boost::asio::io_context io;
  bool stopping = false, ended = false;
  boost::asio::co_spawn(
      io,
      [&]() -> boost::asio::awaitable<void> {
        co_await waitOnClock(board, 1h, stopping);
        ended = true;
      },
      boost::asio::detached);
  boost::asio::steady_timer stopAfter(io, 50ms);
  stopAfter.async_wait([&](const boost::system::error_code&) { stopping = true; });
  io.run_for(5s);
  EXPECT_TRUE(ended);
  EXPECT_LT(Steady::now() - start, 5s);
}

}  // namespace
}  // namespace xr::integrations
