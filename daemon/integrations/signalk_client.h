#pragma once
// Signal K delta client (docs/integrations.md): a WebSocket client (Boost.Beast) on the
// integrations' io_context that pushes deltas to a server's
// /signalk/v1/stream?subscribe=none.
//
//   - meta (units, display names) once per connection, then values at
//     rate_hz; it subscribes to navigation.position (once a minute) for the
//     weather forecast; a change of charging mode, stage or regulator mode goes at once;
//   - newest wins: one delta is written at a time, built from the newest
//     snapshot when the socket is free; nothing queues behind a slow server;
//   - reconnect with exponential backoff, one log line per outage;
//   - secured servers: when the upgrade is refused (401/403) it makes an
//     access request (POST /signalk/v1/access/requests), polls it, and keeps
//     the token it is granted through TokenStore (the state database).
#include <boost/asio/awaitable.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/websocket/stream.hpp>
#include <functional>
#include <optional>
#include <string>

#include "config/settings.h"
#include "integrations/backoff.h"
#include "integrations/boat_position.h"
#include "integrations/integration_health.h"
#include "runtime/handoffs.h"

namespace xr::integrations {

// Persistent strings for the client (the Signal K token and client id).
struct TokenStore {
  std::function<std::optional<std::string>(const std::string& key)> load;
  std::function<void(const std::string& key, const std::string& value)> save;
};

struct WsUrl {
  std::string host, port, target;  // target: path and query
};
// ws://host[:port]/path?query; nullopt when it is not such a URL.
std::optional<WsUrl> parseWsUrl(const std::string& url);

class SignalKClient {
 public:
  // `position`, when given, receives navigation.position from the server
  // (the weather forecast's position; docs/integrations.md "Weather").
  SignalKClient(boost::asio::io_context& io, const SignalKSettings& s, const rt::Handoffs& handoffs,
                TokenStore tokens, const rt::WallClock& clock, SignalKPosition* position = nullptr);
  void start();
  void stop();
  IntegrationStatus status() const { return health_.status(); }

 private:
  boost::asio::awaitable<void> run();
  boost::asio::awaitable<void> session();
  // session()'s parts (signalk_client.cpp).
  using SignalKStream = boost::beast::websocket::stream<boost::beast::tcp_stream>;
  boost::asio::awaitable<void> refuseIfSecured();
  boost::asio::awaitable<void> readDeltas(SignalKStream& ws);
  boost::asio::awaitable<void> writeDeltas(SignalKStream& ws);
  boost::asio::awaitable<void> requestAccess();

  boost::asio::io_context& io_;
  SignalKSettings settings_;
  const rt::WallClock& clock_;  // backoff, delta period, access polling (clock_wait.h)
  const rt::Handoffs& handoffs_;
  TokenStore tokens_;
  SignalKPosition* position_;
  WsUrl url_;
  IntegrationHealth health_;
  Backoff backoff_;
  bool stopping_ = false;
  std::string token_, clientId_, pendingHref_;
};

}  // namespace xr::integrations
