#include "integrations/clock_wait.h"

#include <boost/asio/redirect_error.hpp>
#include <boost/asio/this_coro.hpp>
#include <boost/asio/use_awaitable.hpp>
#include <memory>

namespace xr::integrations {
namespace asio = boost::asio;

asio::awaitable<void> waitOnClock(const rt::WallClock& clock, ClockDuration d, const bool& stopping) {
  asio::steady_timer timer(co_await asio::this_coro::executor);
  co_await waitOnClock(clock, timer, d, stopping);
}

asio::awaitable<void> waitOnClock(const rt::WallClock& clock, asio::steady_timer& timer, ClockDuration d,
                                  const bool& stopping) {
  const auto due = clock.steadyNow() + d;
  while (!stopping) {
    const auto left = due - clock.steadyNow();
    if (left <= ClockDuration::zero()) co_return;
    timer.expires_after(clock.realWait(left));
    boost::system::error_code ec;
    co_await timer.async_wait(asio::redirect_error(asio::use_awaitable, ec));
    if (ec == asio::error::operation_aborted) co_return;
  }
}

namespace {
void waitStep(const rt::WallClock& clock, asio::steady_timer& timer,
              std::chrono::steady_clock::time_point due, std::shared_ptr<std::function<void()>> then) {
  timer.expires_after(clock.realWait(due - clock.steadyNow()));
  timer.async_wait([&clock, &timer, due, then](const boost::system::error_code& ec) {
    if (ec) return;  // cancelled: stopping
    if (clock.steadyNow() >= due)
      (*then)();
    else
      waitStep(clock, timer, due, then);
  });
}
}  // namespace

void afterOnClock(const rt::WallClock& clock, asio::steady_timer& timer, ClockDuration d,
                  std::function<void()> then) {
  waitStep(clock, timer, clock.steadyNow() + d, std::make_shared<std::function<void()>>(std::move(then)));
}

}  // namespace xr::integrations
