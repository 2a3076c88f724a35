#pragma once
// The WebServer's shared state (WebServer::Impl) and the connection counter,
// seen by the listener (web_server.cpp), the HTTP sessions
// (http_session.cpp) and the WebSocket sessions (ws_session.h). Internal to
// web/server.
#include <atomic>
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "web/server/api_handler.h"
#include "web/server/web_server.h"

namespace xr::web {
namespace asio = boost::asio;
namespace beast = boost::beast;
using tcp = asio::ip::tcp;

class WsSession;

struct WebServer::Impl {
  Impl(DaemonApi& a, WebServerOptions o)
      : api(a), opts(std::move(o)), handler(api, opts, [this] { return snapshotStats(); }) {}

  DaemonApi& api;
  WebServerOptions opts;

  std::atomic<std::uint64_t> httpRequests{0}, httpErrors{0}, wsClients{0}, wsSent{0}, wsDropped{0},
      connections{0}, refused{0};
  ApiHandler handler;

  std::mutex wsMutex;
  std::vector<std::weak_ptr<WsSession>> wsSessions;

  std::unique_ptr<asio::io_context> ioc;
  std::unique_ptr<tcp::acceptor> acceptor;
  std::unique_ptr<asio::steady_timer> tickTimer;
  std::vector<std::thread> threads;
  std::uint16_t boundPort = 0;
  std::uint64_t lastSeq = 0;  // touched only by the tick handler
  std::chrono::steady_clock::duration period{};
  bool running = false;

  WebServerStats snapshotStats() const {
    WebServerStats s;
    s.http_requests = httpRequests.load();
    s.http_errors = httpErrors.load();
    s.ws_clients = wsClients.load();
    s.ws_frames_sent = wsSent.load();
    s.ws_frames_dropped = wsDropped.load();
    s.connections = connections.load();
    s.connections_refused = refused.load();
    return s;
  }

  void doAccept();
  void onAccept(beast::error_code ec, tcp::socket socket);
  void scheduleTick();
  void onTick();
  void registerWs(const std::shared_ptr<WsSession>& s) {
    std::lock_guard lock(wsMutex);
    wsSessions.push_back(s);
  }
};

// Counts one open connection for the cap; moves from the HTTP session to the
// WebSocket session on upgrade.
class ConnGuard {
 public:
  explicit ConnGuard(std::atomic<std::uint64_t>& c) : c_(&c) {}
  ConnGuard(ConnGuard&& o) noexcept : c_(std::exchange(o.c_, nullptr)) {}
  ConnGuard& operator=(ConnGuard&&) = delete;
  ~ConnGuard() {
    if (c_) c_->fetch_sub(1);
  }

 private:
  std::atomic<std::uint64_t>* c_;
};

// Serves HTTP requests on an accepted connection (counted in
// impl.connections by the caller) until it closes or upgrades to /ws.
void startHttpSession(tcp::socket&& socket, WebServer::Impl& impl);

}  // namespace xr::web
