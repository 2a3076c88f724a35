// WebServer: Beast listener, HTTP sessions, WebSocket sessions and the
// telemetry broadcaster, all on the server's own Asio threads.
//
// Per docs/architecture.md "Threads" the control thread is never involved: the broadcaster polls
// DaemonApi::latestStatus() (a lock-free copy) at the WebSocket rate,
// serialises the snapshot ONCE and hands the same shared string to every
// client. Each client keeps at most one pending frame (the newest): a slow
// phone replaces its pending frame instead of growing a queue.
//
// This file holds the listener, the broadcaster and start/stop; the sessions
// are in http_session.cpp and ws_session.h, the shared state in
// server_impl.h.
#include "web/server/web_server.h"

#include <algorithm>
#include <boost/asio.hpp>
#include <stdexcept>

#include "web/server/server_impl.h"
#include "web/server/ws_session.h"

namespace xr::web {

void WebServer::Impl::doAccept() {
  acceptor->async_accept(asio::make_strand(*ioc), beast::bind_front_handler(&Impl::onAccept, this));
}

void WebServer::Impl::onAccept(beast::error_code ec, tcp::socket socket) {
  if (ec == asio::error::operation_aborted || !acceptor->is_open()) return;
  if (!ec) {
    beast::error_code aec;
    const auto peer = socket.remote_endpoint(aec).address();
    // Every slot taken: the connection that waited longest for its request
    // gives way (slow clients cannot starve /healthz; docs/security.md).
    const bool full = connections.load() >= static_cast<std::uint64_t>(std::max(1, opts.max_connections));
    if (aec || (full && !evictOldestWaiting()) || !admit(peer)) {
      refused.fetch_add(1);
      static constexpr std::string_view kBusy =
          "HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json\r\nContent-Length: 33\r\n"
          "Connection: close\r\n\r\n{\"error\":\"too many connections\"}\n";
      beast::error_code wec;
      socket.non_blocking(true, wec);
      socket.write_some(asio::buffer(kBusy.data(), kBusy.size()), wec);
      socket.shutdown(tcp::socket::shutdown_both, wec);
      socket.close(wec);
    } else {
      connections.fetch_add(1);
      startHttpSession(std::move(socket), *this, peer);
    }
  }
  doAccept();
}

void WebServer::Impl::scheduleTick() {
  tickTimer->expires_at(tickTimer->expiry() + period);
  tickTimer->async_wait([this](beast::error_code ec) {
    if (ec) return;
    onTick();
    scheduleTick();
  });
}

void WebServer::Impl::onTick() {
  std::uint64_t seq = 0;
  auto msg = handler.statusText(&seq);
  if (!msg || seq == lastSeq) return;
  lastSeq = seq;
  std::vector<std::shared_ptr<WsSession>> live;
  {
    std::lock_guard lock(wsMutex);
    std::erase_if(wsSessions, [](const auto& w) { return w.expired(); });
    live.reserve(wsSessions.size());
    for (const auto& w : wsSessions)
      if (auto s = w.lock()) live.push_back(std::move(s));
  }
  for (auto& s : live) asio::post(s->executor(), [s, msg, seq] { s->deliver(msg, seq); });
}

WebServer::WebServer(DaemonApi& api, WebServerOptions opts)
    : impl_(std::make_unique<Impl>(api, std::move(opts))) {}

WebServer::~WebServer() { stop(); }

void WebServer::start() {
  auto& m = *impl_;
  if (m.running) return;
  if (m.opts.token.empty()) throw std::runtime_error("web: refusing to start without a token");
  const double rate = std::clamp(m.opts.telemetry_rate_hz, 0.2, 20.0);
  m.period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(1.0 / rate));
  const int threads = std::max(1, m.opts.threads);
  m.ioc = std::make_unique<asio::io_context>(threads);
  beast::error_code ec;
  const auto address = asio::ip::make_address(m.opts.listen, ec);
  if (ec) throw std::runtime_error("web: bad listen address '" + m.opts.listen + "': " + ec.message());
  const tcp::endpoint ep{address, m.opts.port};
  m.acceptor = std::make_unique<tcp::acceptor>(asio::make_strand(*m.ioc));
  m.acceptor->open(ep.protocol(), ec);
  if (!ec) m.acceptor->set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) m.acceptor->bind(ep, ec);
  if (!ec) m.acceptor->listen(asio::socket_base::max_listen_connections, ec);
  if (ec) {
    m.acceptor.reset();
    m.ioc.reset();
    throw std::runtime_error("web: cannot listen on " + m.opts.listen + ":" + std::to_string(m.opts.port) +
                             ": " + ec.message());
  }
  m.boundPort = m.acceptor->local_endpoint().port();
  m.doAccept();
  m.tickTimer = std::make_unique<asio::steady_timer>(asio::make_strand(*m.ioc));
  m.tickTimer->expires_after(std::chrono::steady_clock::duration::zero());
  m.scheduleTick();
  m.running = true;
  for (int i = 0; i < threads; ++i)
    m.threads.emplace_back([&m] {
      for (;;) {
        try {
          m.ioc->run();
          return;
        } catch (const std::exception&) {
          // A handler threw: keep serving (the handler already answered 500
          // where it could). Never take the process down from here.
        }
      }
    });
}

void WebServer::stop() {
  auto& m = *impl_;
  if (!m.running) return;
  m.running = false;
  asio::post(m.acceptor->get_executor(), [&m] {
    beast::error_code ec;
    m.acceptor->close(ec);
  });
  m.ioc->stop();
  for (auto& t : m.threads) t.join();
  m.threads.clear();
  m.tickTimer.reset();
  m.acceptor.reset();
  m.ioc.reset();  // destroys pending handlers (and the sessions they hold)
  std::lock_guard lock(m.wsMutex);
  m.wsSessions.clear();
}

std::uint16_t WebServer::port() const { return impl_->boundPort; }

WebServerStats WebServer::stats() const { return impl_->snapshotStats(); }

Pairing::Code WebServer::newPairingCode() { return impl_->handler.pairing().newCode(); }
void WebServer::openFirstStartPairingWindow(std::int64_t durationMs) {
  impl_->handler.pairing().openFirstStartWindow(durationMs);
}
void WebServer::openPresencePairingWindow(std::int64_t durationMs) {
  impl_->handler.pairing().openPresenceWindow(durationMs);
}
bool WebServer::pairingWindowOpen() { return impl_->handler.pairing().window().open; }

}  // namespace xr::web
