#include "integrations/signalk_client.h"

#include <spdlog/spdlog.h>

#include <boost/asio/co_spawn.hpp>
#include <boost/asio/detached.hpp>
#include <boost/asio/experimental/awaitable_operators.hpp>
#include <boost/asio/redirect_error.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/use_awaitable.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/json.hpp>
#include <chrono>
#include <random>
#include <stdexcept>

#include "integrations/clock_wait.h"
#include "integrations/integration_sample.h"
#include "integrations/signalk_delta.h"

namespace xr::integrations {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace json = boost::json;
using asio::use_awaitable;
using tcp = asio::ip::tcp;
using namespace std::chrono_literals;
using namespace asio::experimental::awaitable_operators;

namespace {

constexpr auto kIoTimeout = 10s;
constexpr auto kPollPeriod = 50ms;        // how soon a change of state goes out
constexpr auto kAccessPollPeriod = 2s;    // while an access request waits for approval
constexpr auto kAccessWaitLimit = 10min;  // then a new request
const std::string kTokenKey = "signalk_token";
const std::string kClientIdKey = "signalk_client_id";
// The boat's own position, at most once a minute: the forecast needs no more
// (Signal K subscription protocol: "instant" with minPeriod in ms sends the
// current value at once, then a change at most once a period).
constexpr const char* kPositionSubscription =
    R"({"context":"vessels.self","subscribe":[{"path":"navigation.position","policy":"instant",)"
    R"("minPeriod":60000}]})";

// The server refused us for want of a token (upgrade refused, or a delta
// answered with 401/403).
struct NeedsToken : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string newClientId() {
  // A version-4 UUID, as the access-request API expects for clientId.
  std::random_device rd;
  std::mt19937_64 g((static_cast<std::uint64_t>(rd()) << 32) ^ rd());
  std::uniform_int_distribution<int> hex(0, 15);
  const char* digits = "0123456789abcdef";
  std::string s = "xxxxxxxx-xxxx-4xxx-yxxx-xxxxxxxxxxxx";
  for (char& c : s) {
    if (c == 'x')
      c = digits[hex(g)];
    else if (c == 'y')
      c = digits[8 + hex(g) % 4];
  }
  return s;
}

asio::awaitable<json::value> httpJson(const WsUrl& url, http::verb verb, const std::string& target,
                                      const std::string& body) {
  auto ex = co_await asio::this_coro::executor;
  tcp::resolver resolver(ex);
  const auto hosts = co_await resolver.async_resolve(url.host, url.port, use_awaitable);
  beast::tcp_stream stream(ex);
  stream.expires_after(kIoTimeout);
  co_await stream.async_connect(hosts, use_awaitable);
  http::request<http::string_body> req{verb, target, 11};
  req.set(http::field::host, url.host + ":" + url.port);
  req.set(http::field::user_agent, "xregulatord");
  req.set(http::field::accept, "application/json");
  if (!body.empty()) {
    req.set(http::field::content_type, "application/json");
    req.body() = body;
  }
  req.prepare_payload();
  co_await http::async_write(stream, req, use_awaitable);
  beast::flat_buffer buf;
  http::response<http::string_body> res;
  co_await http::async_read(stream, buf, res, use_awaitable);
  beast::error_code ec;
  stream.socket().shutdown(tcp::socket::shutdown_both, ec);
  json::value v = json::parse(res.body(), ec);
  if (ec) throw std::runtime_error(target + ": HTTP " + std::to_string(res.result_int()) + ", not JSON");
  co_return v;
}

std::string stringAt(const json::value& v, std::initializer_list<const char*> path) {
  const json::value* p = &v;
  for (const char* k : path) {
    if (!p->is_object() || !p->as_object().contains(k)) return {};
    p = &p->as_object().at(k);
  }
  return p->is_string() ? std::string(p->as_string()) : std::string();
}

}  // namespace

std::optional<WsUrl> parseWsUrl(const std::string& url) {
  if (!url.starts_with("ws://")) return std::nullopt;
  const std::string rest = url.substr(5);
  const auto slash = rest.find('/');
  const std::string hostPort = rest.substr(0, slash);
  WsUrl u;
  u.target = slash == std::string::npos ? "/" : rest.substr(slash);
  const auto colon = hostPort.rfind(':');
  u.host = colon == std::string::npos ? hostPort : hostPort.substr(0, colon);
  u.port = colon == std::string::npos ? "80" : hostPort.substr(colon + 1);
  if (u.host.empty() || u.port.empty() || u.port.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return u;
}

SignalKClient::SignalKClient(asio::io_context& io, const SignalKSettings& s, const rt::Handoffs& handoffs,
                             TokenStore tokens, const rt::WallClock& clock, SignalKPosition* position)
    : io_(io),
      settings_(s),
      clock_(clock),
      handoffs_(handoffs),
      tokens_(std::move(tokens)),
      position_(position),
      health_("signalk", clock) {
  auto u = parseWsUrl(s.url);
  if (!u) throw std::runtime_error("signalk: url '" + s.url + "' is not ws://host:port/path");
  url_ = *u;
  if (tokens_.load) {
    token_ = tokens_.load(kTokenKey).value_or("");
    clientId_ = tokens_.load(kClientIdKey).value_or("");
  }
}

void SignalKClient::start() { asio::co_spawn(io_, run(), asio::detached); }

void SignalKClient::stop() { stopping_ = true; }

asio::awaitable<void> SignalKClient::run() {
  while (!stopping_) {
    health_.attempt();
    std::string needsToken;  // why, when the server wants a token
    try {
      co_await session();
    } catch (const NeedsToken& e) {
      needsToken = e.what();
    } catch (const std::exception& e) {
      health_.failed(e.what());
    }
    bool again = false;
    if (!needsToken.empty()) {
      // No token yet, or it was refused: ask for one, then connect at once.
      std::string accessError;
      try {
        co_await requestAccess();
        again = !token_.empty();
      } catch (const std::exception& e) {
        accessError = e.what();
      }
      if (!again)
        health_.failed(needsToken + (accessError.empty() ? "" : "; access request: " + accessError));
    }
    if (stopping_) break;
    if (again) continue;
    co_await waitOnClock(clock_, backoff_.next(), stopping_);
  }
}

asio::awaitable<void> SignalKClient::session() {
  auto ex = co_await asio::this_coro::executor;
  if (token_.empty()) co_await refuseIfSecured();
  tcp::resolver resolver(ex);
  const auto hosts = co_await resolver.async_resolve(url_.host, url_.port, use_awaitable);
  SignalKStream ws(ex);
  beast::get_lowest_layer(ws).expires_after(kIoTimeout);
  co_await beast::get_lowest_layer(ws).async_connect(hosts, use_awaitable);
  const std::string token = token_;
  ws.set_option(websocket::stream_base::decorator([token](websocket::request_type& req) {
    req.set(http::field::user_agent, "xregulatord");
    if (!token.empty()) req.set(http::field::authorization, "Bearer " + token);
  }));
  websocket::response_type res;
  beast::error_code ec;
  co_await ws.async_handshake(res, url_.host + ":" + url_.port, url_.target,
                              asio::redirect_error(use_awaitable, ec));
  if (ec) {
    if (res.result() == http::status::unauthorized || res.result() == http::status::forbidden) {
      if (!token_.empty()) {
        token_.clear();  // refused: revoked or expired
        if (tokens_.save) tokens_.save(kTokenKey, "");
      }
      throw NeedsToken("server is secured: upgrade refused with HTTP " + std::to_string(res.result_int()));
    }
    throw beast::system_error(ec);
  }
  beast::get_lowest_layer(ws).expires_never();
  ws.set_option(websocket::stream_base::timeout::suggested(beast::role_type::client));
  health_.connected();
  backoff_.reset();

  co_await ws.async_write(
      asio::buffer(signalKMetaDelta(signalKMeta(settings_.alternator_id, settings_.battery_id))),
      use_awaitable);
  health_.sent();
  if (position_) {
    co_await ws.async_write(asio::buffer(std::string_view(kPositionSubscription)), use_awaitable);
    health_.sent();
  }
  co_await (readDeltas(ws) || writeDeltas(ws));
}

// A secured signalk-server with read-only access for guests accepts the
// upgrade and then drops every delta without a word; its login status says
// whether a token is needed. Other servers may not have the route.
asio::awaitable<void> SignalKClient::refuseIfSecured() {
  bool secured = false;
  try {
    const json::value st = co_await httpJson(url_, http::verb::get, "/skServer/loginStatus", {});
    secured = st.is_object() && st.as_object().contains("authenticationRequired") &&
              st.as_object().at("authenticationRequired") == json::value(true);
  } catch (const std::exception&) {
    // No such route, or not JSON: not a signalk-server; the upgrade will tell.
  }
  if (secured) throw NeedsToken("server is secured and there is no token yet");
}

// What the server sends: a refusal of our deltas, and the boat's position.
asio::awaitable<void> SignalKClient::readDeltas(SignalKStream& ws) {
  for (;;) {
    beast::flat_buffer buf;
    co_await ws.async_read(buf, use_awaitable);
    health_.received();
    // signalk-server answers a write it does not allow with a 401/403 status.
    beast::error_code pec;
    const json::value v = json::parse(beast::buffers_to_string(buf.data()), pec);
    if (!pec && v.is_object() && v.as_object().contains("statusCode")) {
      const auto& code = v.as_object().at("statusCode");
      if (code.is_int64() && (code.as_int64() == 401 || code.as_int64() == 403))
        throw NeedsToken("server refused a delta: HTTP " + std::to_string(code.as_int64()));
    }
    if (!pec && position_)
      if (auto p = positionFromSignalKDelta(v))
        position_->post(p->latitudeDeg, p->longitudeDeg, clock_.steadyNow());
  }
}

// Our deltas: at rate_hz, and at once when the charging state changes.
asio::awaitable<void> SignalKClient::writeDeltas(SignalKStream& ws) {
  asio::steady_timer t(co_await asio::this_coro::executor);
  const auto period = std::chrono::duration<double>(1.0 / settings_.rate_hz);
  auto lastSent = clock_.steadyNow() - 1h;
  std::string lastState;
  for (;;) {
    const IntegrationSample s = sampleOf(handoffs_.latest(), {handoffs_.setUp.load(), ""});
    if (s.valid) {
      const std::string state = std::string(signalKChargingMode(s.stageValue, s.field_on)) + s.stage + s.mode;
      const auto now = clock_.steadyNow();
      if (state != lastState || now - lastSent >= period) {
        const auto values = signalKValues(s, settings_.alternator_id, settings_.battery_id);
        co_await ws.async_write(asio::buffer(signalKDelta(values, isoTimeUtc(clock_.unixMs()))),
                                use_awaitable);
        health_.sent();
        lastSent = now;
        lastState = state;
      }
    }
    t.expires_after(kPollPeriod);
    co_await t.async_wait(use_awaitable);
  }
}

asio::awaitable<void> SignalKClient::requestAccess() {
  if (clientId_.empty()) {
    clientId_ = newClientId();
    if (tokens_.save) tokens_.save(kClientIdKey, clientId_);
  }
  if (pendingHref_.empty()) {
    json::object body;
    body["clientId"] = clientId_;
    body["description"] = "xregulator alternator regulator";
    body["permissions"] = "readwrite";
    const json::value r =
        co_await httpJson(url_, http::verb::post, "/signalk/v1/access/requests", json::serialize(body));
    pendingHref_ = stringAt(r, {"href"});
    if (pendingHref_.empty())
      throw std::runtime_error("access request not accepted: " + json::serialize(r).substr(0, 200));
    spdlog::warn(
        "signalk: access requested as client {}: approve \"xregulator alternator regulator\" in the Signal K "
        "admin (Security > Access Requests) with read/write",
        clientId_);
  }
  const auto giveUp = clock_.steadyNow() + kAccessWaitLimit;
  while (!stopping_ && clock_.steadyNow() < giveUp) {
    const json::value r = co_await httpJson(url_, http::verb::get, pendingHref_, {});
    if (stringAt(r, {"state"}) == "COMPLETED") {
      pendingHref_.clear();
      if (stringAt(r, {"accessRequest", "permission"}) != "APPROVED")
        throw std::runtime_error("access request denied by the Signal K administrator");
      token_ = stringAt(r, {"accessRequest", "token"});
      if (token_.empty()) throw std::runtime_error("access approved without a token");
      if (tokens_.save) tokens_.save(kTokenKey, token_);
      spdlog::info("signalk: access approved; token kept in the state database");
      co_return;
    }
    co_await waitOnClock(clock_, kAccessPollPeriod, stopping_);
  }
  pendingHref_.clear();
  throw std::runtime_error("access request not approved within 10 minutes");
}

}  // namespace xr::integrations
