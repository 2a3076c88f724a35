// HTTP sessions: read one request at a time under a deadline, answer it
// through ApiHandler, or hand the connection to a WebSocket session on an
// allowed upgrade to /ws.
#include <boost/beast/http.hpp>
#include <optional>
#include <string_view>

#include "web/server/request_checks.h"
#include "web/server/server_impl.h"
#include "web/server/ws_session.h"

namespace xr::web {

namespace {

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket&& socket, WebServer::Impl& impl, const asio::ip::address& peer)
      : stream_(std::move(socket)), impl_(impl), peer_(peer), guard_(impl, peer) {}
  ~HttpSession() { impl_.removeWaiting(waitingId_); }

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
    // Until the request is read, a new connection may close this one when
    // every slot is taken (server_impl.h evictOldestWaiting).
    waitingId_ = impl_.addWaiting([weak = weak_from_this()] {
      if (auto self = weak.lock())
        asio::post(self->stream_.get_executor(), [self] {
          beast::error_code ec;
          self->stream_.socket().shutdown(tcp::socket::shutdown_both, ec);
          self->stream_.socket().close(ec);
        });
    });
    http::async_read(stream_, buffer_, *parser_,
                     beast::bind_front_handler(&HttpSession::onRead, shared_from_this()));
  }

  void onRead(beast::error_code ec, std::size_t) {
    impl_.removeWaiting(waitingId_);
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
    if (auto bad = hostHeaderProblem(req.count(http::field::host), req[http::field::host], req.version());
        !bad.empty())
      return sendResponse(makeError(req, http::status::bad_request, bad));
    if (!hostAllowed(req[http::field::host], impl_.opts.allowed_hosts, machineHostname()))
      return sendResponse(makeError(req, http::status::misdirected_request, "Host not served here"));
    const bool read = req.method() == http::verb::get || req.method() == http::verb::head;
    const bool sameOrigin =
        originAllowed(req[http::field::origin], req[http::field::host], impl_.opts.allowed_origins);
    if (websocket::is_upgrade(req)) {
      if (path != "/ws") return sendResponse(makeError(req, http::status::not_found, "no WebSocket here"));
      if (!sameOrigin) return sendResponse(makeError(req, http::status::forbidden, "Origin not allowed"));
      const auto q = target.find('?');
      const auto token =
          q == std::string_view::npos ? std::nullopt : queryParam(target.substr(q + 1), "token");
      if (auto code = impl_.handler.checkRead(req[http::field::authorization], token.value_or(""))) {
        return sendResponse(makeError(req, code == 401 ? http::status::unauthorized : http::status::forbidden,
                                      code == 401 ? "missing token" : "invalid token"));
      }
      // One address may not hold every slot with WebSockets, and all of
      // them together leave room for /healthz (docs/security.md).
      if (!impl_.reserveWs(peer_))
        return sendResponse(makeError(req, http::status::service_unavailable, "too many WebSocket clients"));
      impl_.httpRequests.fetch_add(1);
      auto ws = std::make_shared<WsSession>(stream_.release_socket(), impl_, std::move(guard_),
                                            ConnGuard(impl_, peer_, true));
      ws->start(req);
      return;
    }
    // A page elsewhere may not write through the owner's browser either.
    if (!read && !sameOrigin)
      return sendResponse(makeError(req, http::status::forbidden, "Origin not allowed"));
    sendResponse(impl_.handler.handle(req, peer_));
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
  asio::ip::address peer_;
  ConnGuard guard_;
  std::optional<http::request_parser<http::string_body>> parser_;
  bool first_ = true;
  std::uint64_t waitingId_ = 0;  // 0: not waiting
};

}  // namespace

void startHttpSession(tcp::socket&& socket, WebServer::Impl& impl, const asio::ip::address& peer) {
  std::make_shared<HttpSession>(std::move(socket), impl, peer)->run();
}

}  // namespace xr::web
