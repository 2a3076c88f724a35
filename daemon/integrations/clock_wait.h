#pragma once
// Waiting on the one clock below the core (runtime/wall_clock.h): the
// integrations' refreshes, backoffs, timeouts and publish periods are
// durations of that clock, so in --sim they pass at the simulation's speed
// and a test of a one-minute refresh does not wait a real minute
// (docs/architecture.md "One clock"). A real timer waits in steps of
// WallClock::realWait and the clock is asked again after each.
#include <boost/asio/awaitable.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>

#include "runtime/wall_clock.h"

namespace xr::integrations {

using ClockDuration = std::chrono::steady_clock::duration;

// Returns once `d` of `clock` has passed, as soon as `stopping` is true, or
// when the wait is cancelled (the other side of an `||` finished first).
boost::asio::awaitable<void> waitOnClock(const rt::WallClock& clock, ClockDuration d, const bool& stopping);
// The same on a timer of the caller's, so that cancelling it (a new job to
// do, or stop) ends the wait early.
boost::asio::awaitable<void> waitOnClock(const rt::WallClock& clock, boost::asio::steady_timer& timer,
                                         ClockDuration d, const bool& stopping);

// Calls `then` on the timer's executor once `d` of `clock` has passed;
// never when the timer is cancelled (stop) first.
void afterOnClock(const rt::WallClock& clock, boost::asio::steady_timer& timer, ClockDuration d,
                  std::function<void()> then);

}  // namespace xr::integrations
