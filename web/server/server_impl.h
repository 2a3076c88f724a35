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
#include <functional>
#include <map>
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
      connections{0}, refused{0}, evicted{0};
  ApiHandler handler;

  // Per-address counts for the per-client bounds: {connections, WebSockets}.
  std::mutex ipMutex;
  std::map<asio::ip::address, std::pair<int, int>> perIp;
  int wsReserved = 0;  // under ipMutex

  int limitPerIp() const {
    return opts.max_per_ip > 0 ? opts.max_per_ip : std::max(1, opts.max_connections * 3 / 4);
  }
  int limitWsPerIp() const {
    return opts.max_ws_per_ip > 0 ? opts.max_ws_per_ip : std::max(1, opts.max_connections / 4);
  }
  int limitWs() const { return std::max(1, opts.max_connections - std::max(1, opts.max_connections / 8)); }
  // False when this address already holds its share of connections.
  bool admit(const asio::ip::address& a) {
    std::lock_guard lock(ipMutex);
    auto& c = perIp[a];
    if (c.first >= limitPerIp()) {
      if (c.first == 0 && c.second == 0) perIp.erase(a);
      return false;
    }
    ++c.first;
    return true;
  }
  void release(const asio::ip::address& a, bool ws) {
    std::lock_guard lock(ipMutex);
    auto it = perIp.find(a);
    if (it == perIp.end()) return;
    if (ws) {
      --it->second.second;
      --wsReserved;
    } else {
      --it->second.first;
    }
    if (it->second.first <= 0 && it->second.second <= 0) perIp.erase(it);
  }
  bool reserveWs(const asio::ip::address& a) {
    std::lock_guard lock(ipMutex);
    auto& c = perIp[a];
    if (c.second >= limitWsPerIp() || wsReserved >= limitWs()) return false;
    ++c.second;
    ++wsReserved;
    return true;
  }

  // Connections reading a request (headers or body), oldest first by id:
  // what a new connection may close when every slot is taken.
  struct Waiting {
    std::chrono::steady_clock::time_point since;
    std::function<void()> evict;  // posts a close to the session's strand
  };
  std::mutex waitingMutex;
  std::map<std::uint64_t, Waiting> waiting;
  std::uint64_t nextWaitingId = 0;  // under waitingMutex
  std::uint64_t addWaiting(std::function<void()> evict) {
    std::lock_guard lock(waitingMutex);
    waiting.emplace(++nextWaitingId, Waiting{std::chrono::steady_clock::now(), std::move(evict)});
    return nextWaitingId;
  }
  void removeWaiting(std::uint64_t id) {
    std::lock_guard lock(waitingMutex);
    waiting.erase(id);
  }
  // Closes the connection that has waited longest for its request, when it
  // has waited evict_waiting_after; true when one was told to close.
  bool evictOldestWaiting() {
    std::function<void()> evict;
    {
      std::lock_guard lock(waitingMutex);
      auto it = waiting.begin();  // ids rise with time: the first waited longest
      if (it == waiting.end() ||
          std::chrono::steady_clock::now() - it->second.since < opts.evict_waiting_after)
        return false;
      evict = std::move(it->second.evict);
      waiting.erase(it);
    }
    evicted.fetch_add(1);
    evict();
    return true;
  }

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
    s.connections_evicted = evicted.load();
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

// Counts one open connection (or, ws = true, one WebSocket) of an address
// for the caps; moves from the HTTP session to the WebSocket session on
// upgrade.
class ConnGuard {
 public:
  ConnGuard(WebServer::Impl& impl, asio::ip::address a, bool ws = false) : impl_(&impl), a_(a), ws_(ws) {}
  ConnGuard(ConnGuard&& o) noexcept : impl_(std::exchange(o.impl_, nullptr)), a_(o.a_), ws_(o.ws_) {}
  ConnGuard& operator=(ConnGuard&&) = delete;
  ~ConnGuard() {
    if (!impl_) return;
    if (!ws_) impl_->connections.fetch_sub(1);
    impl_->release(a_, ws_);
  }

 private:
  WebServer::Impl* impl_;
  asio::ip::address a_;
  bool ws_;
};

// Serves HTTP requests on an accepted connection (counted in
// impl.connections by the caller) until it closes or upgrades to /ws.
// peer: the client's address, already admitted (Impl::admit).
void startHttpSession(tcp::socket&& socket, WebServer::Impl& impl, const asio::ip::address& peer);

}  // namespace xr::web
