#pragma once
// The generic push (docs/integrations.md "Alarms that reach the owner"): one
// HTTP(S) POST per incident start and end to [notify] url, on the
// integrations' io_context, never the control thread.
//
// Each edge is delivered at most once: it leaves the queue after a 2xx
// answer, or after an answer that says it will never be taken (4xx other
// than 408 and 429: a wrong token, a wrong path), which is logged. While the
// network is down, the receiver answers 5xx, 408 or 429, or takes longer
// than timeout_s, the edge stays first in line and is retried with backoff
// (2 s, 4 s ... 5 min), so the owner gets the start and the end, in order,
// once the receiver is back. timeout_s and the backoff run on the clock of
// clock_wait.h (simulated time in --sim). The queue is bounded (kQueueLimit
// edges); an edge that would overflow it is dropped and counted.
#include <atomic>
#include <boost/asio/awaitable.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <deque>
#include <exception>
#include <optional>
#include <string>
#include <utility>

#include "config/notify_target.h"
#include "config/settings.h"
#include "integrations/backoff.h"
#include "integrations/integration_health.h"
#include "integrations/push_message.h"

namespace xr::integrations {

class PushNotifier {
 public:
  static constexpr std::size_t kQueueLimit = 64;

  // Throws std::runtime_error on a URL or header the loader would refuse.
  PushNotifier(boost::asio::io_context& io, const NotifySettings& s, std::string regulator,
               const rt::WallClock& clock);
  void start();
  void stop();
  // On the io_context's thread: queue one edge for delivery.
  void notify(const IncidentEdge& e);
  IntegrationStatus status() const;
  const std::string& regulator() const { return regulator_; }

 private:
  boost::asio::awaitable<void> run();
  // One attempt: the HTTP status, or throws on a network error or timeout.
  boost::asio::awaitable<int> deliver(const PushMessage& m);
  boost::asio::awaitable<std::pair<int, std::exception_ptr>> deliverCaught(const PushMessage& m);
  boost::asio::awaitable<int> deliverUntimed(const PushMessage& m);

  boost::asio::io_context& io_;
  NotifySettings settings_;
  NotifyUrl url_;
  std::optional<NotifyHeader> header_;
  std::string regulator_;
  const rt::WallClock& clock_;  // timeout_s and the backoff run on it
  IntegrationHealth health_;
  Backoff backoff_;
  boost::asio::steady_timer wake_;
  std::deque<PushMessage> queue_;
  std::atomic<std::size_t> queued_{0};  // queue_.size() for the web threads
  bool stopping_ = false;
};

// The board's host name, for [notify] name = "" (the regulator's name in a message).
std::string boardName();

}  // namespace xr::integrations
