// WebServer: Beast listener, HTTP sessions, WebSocket sessions and the
// telemetry broadcaster, all on the server's own Asio threads.
//
// Per DESIGN.md the control thread is never involved: the broadcaster polls
// DaemonApi::latestStatus() (a lock-free copy) at the WebSocket rate,
// serialises the snapshot ONCE and hands the same shared string to every
// client. Each client keeps at most one pending frame (the newest): a slow
// phone replaces its pending frame instead of growing a queue.
#include "web/server/web_server.h"

#include <algorithm>
#include <atomic>
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "web/server/api_handler.h"

namespace xr::web {
namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
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

namespace {

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

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// WebSocket upgrades from a browser carry Origin; it must name this host (or
// a configured origin), so a web page elsewhere cannot read the boat's data
// through the owner's browser. Non-browser clients send no Origin.
bool originAllowed(const Request& req, const WebServerOptions& opts) {
  const std::string_view origin = req[http::field::origin];
  if (origin.empty()) return true;
  for (const auto& o : opts.allowed_origins)
    if (iequals(origin, o)) return true;
  const auto scheme = origin.find("://");
  if (scheme == std::string_view::npos) return false;
  const std::string_view host = origin.substr(scheme + 3);
  const std::string_view reqHost = req[http::field::host];
  return !reqHost.empty() && iequals(host, reqHost);
}

}  // namespace

class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(tcp::socket&& socket, WebServer::Impl& impl, ConnGuard guard)
      : ws_(std::move(socket)), impl_(impl), guard_(std::move(guard)) {}

  ~WsSession() {
    if (counted_) impl_.wsClients.fetch_sub(1);
  }

  void start(const Request& req) {
    beast::get_lowest_layer(ws_).expires_never();  // the websocket timeout takes over
    if (impl_.opts.ws_send_buffer > 0) {
      beast::error_code ec;
      beast::get_lowest_layer(ws_).socket().set_option(
          asio::socket_base::send_buffer_size(impl_.opts.ws_send_buffer), ec);
    }
    websocket::stream_base::timeout to{};
    to.handshake_timeout = impl_.opts.request_timeout;
    to.idle_timeout = impl_.opts.ws_idle_timeout;  // ping at half, close when no reply
    to.keep_alive_pings = true;
    ws_.set_option(to);
    ws_.set_option(websocket::stream_base::decorator(
        [](websocket::response_type& res) { res.set(http::field::server, "xregulatord"); }));
    ws_.read_message_max(4096);  // clients only send pings/close; nothing big
    ws_.async_accept(req, beast::bind_front_handler(&WsSession::onAccept, shared_from_this()));
  }

  // Called on this session's strand with the shared frame of the newest tick.
  void deliver(std::shared_ptr<const std::string> msg) {
    if (closed_) return;
    if (writing_) {
      if (pending_) impl_.wsDropped.fetch_add(1);
      pending_ = std::move(msg);  // keep only the newest
      return;
    }
    write(std::move(msg));
  }

  asio::any_io_executor executor() { return ws_.get_executor(); }

 private:
  void onAccept(beast::error_code ec) {
    if (ec) return;
    counted_ = true;
    impl_.wsClients.fetch_add(1);
    impl_.registerWs(shared_from_this());
    if (auto first = impl_.handler.statusText()) deliver(std::move(first));
    doRead();
  }

  void doRead() {
    ws_.async_read(buffer_, beast::bind_front_handler(&WsSession::onRead, shared_from_this()));
  }

  void onRead(beast::error_code ec, std::size_t) {
    if (ec) {
      closed_ = true;
      pending_.reset();
      return;
    }
    buffer_.consume(buffer_.size());  // client messages are ignored
    doRead();
  }

  void write(std::shared_ptr<const std::string> msg) {
    writing_ = true;
    current_ = std::move(msg);
    ws_.text(true);
    ws_.async_write(asio::buffer(*current_),
                    beast::bind_front_handler(&WsSession::onWrite, shared_from_this()));
  }

  void onWrite(beast::error_code ec, std::size_t) {
    writing_ = false;
    current_.reset();
    if (ec) {
      closed_ = true;
      pending_.reset();
      return;
    }
    impl_.wsSent.fetch_add(1);
    if (pending_) write(std::exchange(pending_, nullptr));
  }

  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  WebServer::Impl& impl_;
  ConnGuard guard_;
  std::shared_ptr<const std::string> current_, pending_;
  bool writing_ = false;
  bool closed_ = false;
  bool counted_ = false;
};

namespace {

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket&& socket, WebServer::Impl& impl)
      : stream_(std::move(socket)), impl_(impl), guard_(impl.connections) {}

  void run() {
    asio::dispatch(stream_.get_executor(),
                   beast::bind_front_handler(&HttpSession::doRead, shared_from_this()));
  }

 private:
  void doRead() {
    parser_.emplace();
    parser_->header_limit(static_cast<std::uint32_t>(impl_.opts.header_limit));
    parser_->body_limit(impl_.opts.body_limit);
    // One deadline for the whole request: a client dripping bytes is cut off.
    stream_.expires_after(first_ ? impl_.opts.request_timeout : impl_.opts.keepalive_timeout);
    first_ = false;
    http::async_read(stream_, buffer_, *parser_,
                     beast::bind_front_handler(&HttpSession::onRead, shared_from_this()));
  }

  void onRead(beast::error_code ec, std::size_t) {
    if (ec == http::error::end_of_stream) return close();
    if (ec == http::error::body_limit)
      return sendError(http::status::payload_too_large, "request body too large");
    if (ec == http::error::header_limit)
      return sendError(http::status::request_header_fields_too_large, "request headers too large");
    if (ec && ec.category() == beast::http::make_error_code(http::error::bad_target).category() &&
        ec != http::error::partial_message)
      return sendError(http::status::bad_request, "malformed HTTP request: " + ec.message());
    if (ec) return;  // timeout, reset, partial message: just drop the connection

    Request req = parser_->release();
    const std::string_view target = req.target();
    const std::string_view path = target.substr(0, target.find('?'));
    if (websocket::is_upgrade(req)) {
      if (path != "/ws") return sendResponse(makeError(req, http::status::not_found, "no WebSocket here"));
      if (!originAllowed(req, impl_.opts))
        return sendResponse(makeError(req, http::status::forbidden, "Origin not allowed"));
      const auto q = target.find('?');
      const auto token =
          q == std::string_view::npos ? std::nullopt : queryParam(target.substr(q + 1), "token");
      if (auto code = impl_.handler.checkRead(req[http::field::authorization], token.value_or(""))) {
        return sendResponse(makeError(req, code == 401 ? http::status::unauthorized : http::status::forbidden,
                                      code == 401 ? "missing token" : "invalid token"));
      }
      impl_.httpRequests.fetch_add(1);
      auto ws = std::make_shared<WsSession>(stream_.release_socket(), impl_, std::move(guard_));
      ws->start(req);
      return;
    }
    sendResponse(impl_.handler.handle(req));
  }

  Response makeError(const Request& req, http::status status, std::string_view msg) {
    Response res{status, req.version()};
    res.set(http::field::content_type, "application/json");
    res.body() = "{\"error\":\"" + std::string(msg) + "\"}";
    res.keep_alive(false);
    res.prepare_payload();
    return res;
  }

  void sendError(http::status status, const std::string& msg) {
    Request dummy;
    dummy.version(11);
    std::string clean;
    for (char c : msg)
      if (c != '"' && c != '\\' && static_cast<unsigned char>(c) >= 0x20) clean.push_back(c);
    sendResponse(makeError(dummy, status, clean));
  }

  void sendResponse(Response res) {
    impl_.httpRequests.fetch_add(1);
    if (res.result_int() >= 400) impl_.httpErrors.fetch_add(1);
    auto sp = std::make_shared<Response>(std::move(res));
    stream_.expires_after(impl_.opts.request_timeout);
    http::async_write(stream_, *sp, [self = shared_from_this(), sp](beast::error_code ec, std::size_t) {
      if (ec) return;
      if (!sp->keep_alive()) return self->close();
      self->doRead();
    });
  }

  void close() {
    beast::error_code ec;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
  }

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  WebServer::Impl& impl_;
  ConnGuard guard_;
  std::optional<http::request_parser<http::string_body>> parser_;
  bool first_ = true;
};

}  // namespace

void WebServer::Impl::doAccept() {
  acceptor->async_accept(asio::make_strand(*ioc), beast::bind_front_handler(&Impl::onAccept, this));
}

void WebServer::Impl::onAccept(beast::error_code ec, tcp::socket socket) {
  if (ec == asio::error::operation_aborted || !acceptor->is_open()) return;
  if (!ec) {
    if (connections.load() >= static_cast<std::uint64_t>(std::max(1, opts.max_connections))) {
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
      std::make_shared<HttpSession>(std::move(socket), *this)->run();
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
  for (auto& s : live) asio::post(s->executor(), [s, msg] { s->deliver(msg); });
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

}  // namespace xr::web
