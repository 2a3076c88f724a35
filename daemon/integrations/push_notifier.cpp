#include "integrations/push_notifier.h"

#include <openssl/ssl.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <boost/asio/co_spawn.hpp>
#include <boost/asio/detached.hpp>
#include <boost/asio/experimental/awaitable_operators.hpp>
#include <boost/asio/redirect_error.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/asio/use_awaitable.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <stdexcept>
#include <variant>

#include "integrations/clock_wait.h"

namespace xr::integrations {
namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace ssl = asio::ssl;
using asio::use_awaitable;
using tcp = asio::ip::tcp;
using namespace std::chrono_literals;
using namespace asio::experimental::awaitable_operators;

namespace {
// An answer is a few bytes; a larger one is not read.
constexpr std::size_t kAnswerLimit = 16 * 1024;

// A status that says this edge will never be taken as it is: not retried.
bool refusedForGood(int status) { return status >= 400 && status < 500 && status != 408 && status != 429; }

// Writes the request and reads the answer on any connected stream.
template <class Stream>
asio::awaitable<int> exchange(Stream& stream, http::request<http::string_body>& req) {
  co_await http::async_write(stream, req, use_awaitable);
  beast::flat_buffer buf;
  http::response_parser<http::string_body> parser;
  parser.body_limit(kAnswerLimit);
  co_await http::async_read(stream, buf, parser, use_awaitable);
  co_return parser.get().result_int();
}
}  // namespace

std::string boardName() {
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) != 0 || !host[0]) return "xregulator";
  return host;
}

PushNotifier::PushNotifier(asio::io_context& io, const NotifySettings& s, std::string regulator,
                           const rt::WallClock& clock)
    : io_(io),
      settings_(s),
      regulator_(regulator.empty() ? boardName() : std::move(regulator)),
      clock_(clock),
      health_("notify", clock),
      backoff_(std::chrono::milliseconds(2s), std::chrono::milliseconds(5min)),
      wake_(io) {
  std::string why;
  auto u = parseNotifyUrl(s.url, &why);
  if (!u) throw std::runtime_error("notify: url '" + s.url + "' " + why);
  url_ = *u;
  if (!s.header.empty()) {
    header_ = parseNotifyHeader(s.header, &why);
    if (!header_) throw std::runtime_error("notify: header " + why);
  }
}

void PushNotifier::start() { asio::co_spawn(io_, run(), asio::detached); }

void PushNotifier::stop() {
  stopping_ = true;
  wake_.cancel();
  // What could not be sent is said once, so the journal tells the owner why no push came.
  if (!queue_.empty())
    spdlog::warn("notify: {} incident message(s) not delivered at stop (the receiver did not take them)",
                 queue_.size());
}

void PushNotifier::notify(const IncidentEdge& e) {
  if (queue_.size() >= kQueueLimit) {
    health_.dropped();
    spdlog::warn("notify: {} messages wait already; incident {} {} dropped", queue_.size(), e.incident.id,
                 e.start ? "start" : "end");
    return;
  }
  queue_.push_back(pushMessage(e, regulator_, settings_.format));
  queued_ = queue_.size();
  wake_.cancel();  // the sender may be waiting for work
}

asio::awaitable<void> PushNotifier::run() {
  while (!stopping_) {
    if (queue_.empty()) {
      wake_.expires_after(24h);
      beast::error_code ec;
      co_await wake_.async_wait(asio::redirect_error(use_awaitable, ec));
      continue;
    }
    const PushMessage m = queue_.front();
    health_.attempt();
    std::string error;
    int status = 0;
    try {
      status = co_await deliver(m);
    } catch (const boost::system::system_error& e) {
      error = e.code() == beast::error::timeout
                  ? "no answer within " + std::to_string(settings_.timeout_s) + " s"
                  : e.code().message();  // what() carries Beast's source location: not for the user
    } catch (const std::exception& e) {
      error = e.what();
    }
    if (stopping_) break;
    const char* edge = m.start ? "start" : "end";
    if (error.empty() && status >= 200 && status < 300) {
      queue_.pop_front();
      queued_ = queue_.size();
      health_.connected();
      health_.sent();
      backoff_.reset();
      spdlog::info("notify: incident {} {} delivered (HTTP {})", m.incidentId, edge, status);
      continue;
    }
    if (error.empty() && refusedForGood(status)) {
      // Retrying cannot help (a wrong token or path): say so once, keep the queue moving.
      queue_.pop_front();
      queued_ = queue_.size();
      health_.connected();
      health_.refused("incident " + std::to_string(m.incidentId) + " " + edge + " refused with HTTP " +
                      std::to_string(status) + ": check [notify] url and header");
      spdlog::error("notify: the receiver refused incident {} {} with HTTP {}; check [notify] url and header",
                    m.incidentId, edge, status);
      continue;
    }
    const auto wait = backoff_.next();
    health_.failed((error.empty() ? "receiver answered HTTP " + std::to_string(status) : error) +
                   "; next try in " + std::to_string(wait.count() / 1000) + " s");
    co_await waitOnClock(clock_, wake_, wait, stopping_);  // a new edge (notify) ends it early
  }
}

// One deadline for connect, write and read, timeout_s on the clock: the
// attempt that loses the race is cancelled. Its failure is caught and thrown
// again here, as `||` waits for a success (weather_client.cpp fetch).
asio::awaitable<int> PushNotifier::deliver(const PushMessage& m) {
  auto r = co_await (deliverCaught(m) ||
                     waitOnClock(clock_, std::chrono::seconds(settings_.timeout_s), stopping_));
  if (r.index() == 1) throw boost::system::system_error(beast::error::timeout);
  auto [status, error] = std::get<0>(r);
  if (error) std::rethrow_exception(error);
  co_return status;
}

asio::awaitable<std::pair<int, std::exception_ptr>> PushNotifier::deliverCaught(const PushMessage& m) {
  try {
    co_return std::make_pair(co_await deliverUntimed(m), std::exception_ptr{});
  } catch (...) {
    co_return std::make_pair(0, std::current_exception());
  }
}

asio::awaitable<int> PushNotifier::deliverUntimed(const PushMessage& m) {
  http::request<http::string_body> req{http::verb::post, url_.target, 11};
  const bool defaultPort = url_.port == (url_.tls ? "443" : "80");
  req.set(http::field::host, defaultPort ? url_.host : url_.host + ":" + url_.port);
  req.set(http::field::user_agent, "xregulatord");
  req.set(http::field::content_type, m.contentType);
  for (const auto& [name, value] : m.headers) req.set(name, value);
  if (header_) req.set(header_->name, header_->value);
  req.body() = m.body;
  req.prepare_payload();

  auto ex = co_await asio::this_coro::executor;
  tcp::resolver resolver(ex);
  const auto hosts = co_await resolver.async_resolve(url_.host, url_.port, use_awaitable);
  if (!url_.tls) {
    beast::tcp_stream stream(ex);
    co_await stream.async_connect(hosts, use_awaitable);
    const int status = co_await exchange(stream, req);
    beast::error_code ec;
    stream.socket().shutdown(tcp::socket::shutdown_both, ec);
    co_return status;
  }
  // https: the system's trust store, the name checked against the certificate.
  ssl::context ctx(ssl::context::tls_client);
  ctx.set_default_verify_paths();
  ctx.set_verify_mode(ssl::verify_peer);
  beast::ssl_stream<beast::tcp_stream> stream(ex, ctx);
  if (!SSL_set_tlsext_host_name(stream.native_handle(), url_.host.c_str()))
    throw std::runtime_error("TLS: cannot set the server name");
  stream.set_verify_callback(ssl::host_name_verification(url_.host));
  co_await beast::get_lowest_layer(stream).async_connect(hosts, use_awaitable);
  co_await stream.async_handshake(ssl::stream_base::client, use_awaitable);
  const int status = co_await exchange(stream, req);
  beast::error_code ec;
  beast::get_lowest_layer(stream).socket().shutdown(tcp::socket::shutdown_both, ec);
  co_return status;
}

IntegrationStatus PushNotifier::status() const {
  IntegrationStatus s = health_.status();
  s.values["queued"] = static_cast<double>(queued_.load());
  return s;
}

}  // namespace xr::integrations
