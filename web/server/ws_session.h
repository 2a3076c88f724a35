#pragma once
// One WebSocket client: receives the shared telemetry frame of each tick and
// keeps at most one pending frame (the newest), so a slow phone replaces its
// pending frame instead of growing a queue. Internal to web/server.
#include <boost/beast/websocket.hpp>
#include <memory>
#include <string>

#include "web/server/server_impl.h"

namespace xr::web {
namespace websocket = beast::websocket;

class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(tcp::socket&& socket, WebServer::Impl& impl, ConnGuard guard, ConnGuard wsSlot)
      : ws_(std::move(socket)),
        impl_(impl),
        guard_(std::move(guard)),
        wsSlot_(std::move(wsSlot)),
        writeTimer_(ws_.get_executor()) {}

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

  // Called on this session's strand with the shared frame of the newest tick
  // and its sequence number. A frame not newer than the last one taken is
  // dropped: the greeting frame of onAccept and the broadcaster's frame of
  // the same tick can both reach a client that registered while that tick
  // was being broadcast (seen on a slow CPU: qemu-user), and an older frame
  // posted before the greeting must not follow it.
  void deliver(std::shared_ptr<const std::string> msg, std::uint64_t seq) {
    if (closed_ || seq <= lastSeq_) return;
    lastSeq_ = seq;
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
    std::uint64_t seq = 0;
    if (auto first = impl_.handler.statusText(&seq)) deliver(std::move(first), seq);
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
    // A client that never reads keeps pinging, so the idle timeout never
    // fires; a frame it does not take in time closes it (docs/security.md).
    writeTimer_.expires_after(impl_.opts.ws_write_timeout);
    writeTimer_.async_wait([self = shared_from_this()](beast::error_code ec) {
      if (ec || !self->writing_) return;
      self->closed_ = true;
      beast::error_code cec;
      beast::get_lowest_layer(self->ws_).socket().close(cec);
    });
    ws_.async_write(asio::buffer(*current_),
                    beast::bind_front_handler(&WsSession::onWrite, shared_from_this()));
  }

  void onWrite(beast::error_code ec, std::size_t) {
    writing_ = false;
    writeTimer_.cancel();
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
  ConnGuard wsSlot_;
  asio::steady_timer writeTimer_;
  std::shared_ptr<const std::string> current_, pending_;
  std::uint64_t lastSeq_ = 0;  // of the newest frame taken; 0 = none yet
  bool writing_ = false;
  bool closed_ = false;
  bool counted_ = false;
};

}  // namespace xr::web
