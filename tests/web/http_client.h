#pragma once
// Minimal synchronous Beast HTTP/WebSocket clients for the API tests. Every
// socket carries a generous deadline so a broken server fails a test instead
// of hanging it (a safety net, never an assertion about speed).
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <map>
#include <string>

namespace xr::web::test {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace bhttp = boost::beast::http;
namespace websocket = boost::beast::websocket;
using tcp = asio::ip::tcp;

inline constexpr auto kSafetyNet = std::chrono::seconds(20);

struct HttpResult {
  int status = 0;
  std::string body;
  mutable std::map<std::string, std::string> headers;  // mutable: tests index absent headers as ""
};

inline HttpResult httpRequest(std::uint16_t port, bhttp::verb method, const std::string& target,
                              const std::string& body = "",
                              const std::map<std::string, std::string>& headers = {}) {
  asio::io_context ioc;
  beast::tcp_stream stream(ioc);
  stream.expires_after(kSafetyNet);
  stream.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
  bhttp::request<bhttp::string_body> req{method, target, 11};
  req.set(bhttp::field::host, "127.0.0.1:" + std::to_string(port));
  for (const auto& [k, v] : headers) req.set(k, v);
  if (!body.empty() || method == bhttp::verb::patch || method == bhttp::verb::post) {
    req.set(bhttp::field::content_type, "application/json");
    req.body() = body;
    req.prepare_payload();
  }
  bhttp::write(stream, req);
  beast::flat_buffer buf;
  bhttp::response_parser<bhttp::string_body> parser;
  parser.body_limit(64 * 1024 * 1024);
  if (method == bhttp::verb::head) parser.skip(true);
  bhttp::read(stream, buf, parser);
  auto res = parser.release();
  HttpResult r;
  r.status = res.result_int();
  r.body = res.body();
  for (const auto& f : res) r.headers[std::string(f.name_string())] = std::string(f.value());
  beast::error_code ec;
  stream.socket().shutdown(tcp::socket::shutdown_both, ec);
  return r;
}

// Sends raw bytes and returns whatever comes back until the server closes.
inline std::string rawExchange(std::uint16_t port, const std::string& bytes) {
  asio::io_context ioc;
  beast::tcp_stream stream(ioc);
  stream.expires_after(kSafetyNet);
  stream.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
  beast::error_code ec;
  asio::write(stream, asio::buffer(bytes), ec);
  std::string out;
  char buf[4096];
  for (;;) {
    const auto n = stream.read_some(asio::buffer(buf), ec);
    out.append(buf, n);
    if (ec) break;
    // Stop after one full response header + body the server closes after.
  }
  return out;
}

class WsClient {
 public:
  // Throws beast::system_error when the upgrade is refused.
  WsClient(std::uint16_t port, const std::string& target = "/ws", const std::string& origin = "")
      : ws_(ioc_) {
    beast::get_lowest_layer(ws_).expires_after(kSafetyNet);
    beast::get_lowest_layer(ws_).connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
    if (!origin.empty())
      ws_.set_option(websocket::stream_base::decorator(
          [origin](websocket::request_type& req) { req.set(bhttp::field::origin, origin); }));
    ws_.handshake(res_, "127.0.0.1:" + std::to_string(port), target);
  }
  std::string read() {
    beast::get_lowest_layer(ws_).expires_after(kSafetyNet);
    beast::flat_buffer buf;
    ws_.read(buf);
    return beast::buffers_to_string(buf.data());
  }
  void close() {
    beast::error_code ec;
    ws_.close(websocket::close_code::normal, ec);
  }

 private:
  asio::io_context ioc_;
  websocket::stream<beast::tcp_stream> ws_;
  websocket::response_type res_;
};

// Status code of a refused upgrade (the HTTP response the server sent).
inline int wsUpgradeStatus(std::uint16_t port, const std::string& target, const std::string& origin) {
  asio::io_context ioc;
  websocket::stream<beast::tcp_stream> ws(ioc);
  beast::get_lowest_layer(ws).expires_after(kSafetyNet);
  beast::get_lowest_layer(ws).connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
  if (!origin.empty())
    ws.set_option(websocket::stream_base::decorator(
        [origin](websocket::request_type& req) { req.set(bhttp::field::origin, origin); }));
  websocket::response_type res;
  beast::error_code ec;
  ws.handshake(res, "127.0.0.1:" + std::to_string(port), target, ec);
  return res.result_int();
}

}  // namespace xr::web::test
