// xr_ws_clients: N WebSocket clients on one Asio thread, each reading
// telemetry frames for D seconds. Prints "clients=N frames=F bytes=B errors=E".
// Used by run-web.sh beside wrk; never a test.
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

struct Totals {
  std::uint64_t frames = 0, bytes = 0, errors = 0;
};

struct Client : std::enable_shared_from_this<Client> {
  Client(asio::io_context& ioc, Totals& t) : ws(ioc), totals(t) {}
  void start(const tcp::endpoint& ep, const std::string& host) {
    beast::get_lowest_layer(ws).async_connect(ep, [self = shared_from_this(), host](beast::error_code ec) {
      if (ec) return self->fail();
      beast::get_lowest_layer(self->ws).expires_never();
      self->ws.async_handshake(host, "/ws", [self](beast::error_code ec2) {
        if (ec2) return self->fail();
        self->read();
      });
    });
  }
  void read() {
    ws.async_read(buf, [self = shared_from_this()](beast::error_code ec, std::size_t n) {
      if (ec) {
        if (ec != asio::error::operation_aborted) self->fail();
        return;
      }
      ++self->totals.frames;
      self->totals.bytes += n;
      self->buf.consume(self->buf.size());
      self->read();
    });
  }
  void fail() { ++totals.errors; }
  websocket::stream<beast::tcp_stream> ws;
  beast::flat_buffer buf;
  Totals& totals;
};

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: xr_ws_clients PORT CLIENTS SECONDS\n");
    return 2;
  }
  const auto port = static_cast<unsigned short>(std::stoi(argv[1]));
  const int n = std::stoi(argv[2]);
  const int seconds = std::stoi(argv[3]);
  asio::io_context ioc;
  Totals totals;
  const tcp::endpoint ep(asio::ip::make_address("127.0.0.1"), port);
  std::vector<std::shared_ptr<Client>> clients;
  for (int i = 0; i < n; ++i) {
    clients.push_back(std::make_shared<Client>(ioc, totals));
    clients.back()->start(ep, "127.0.0.1:" + std::to_string(port));
  }
  asio::steady_timer stop(ioc, std::chrono::seconds(seconds));
  stop.async_wait([&](beast::error_code) { ioc.stop(); });
  ioc.run();
  std::printf("clients=%d frames=%llu bytes=%llu errors=%llu\n", n,
              static_cast<unsigned long long>(totals.frames), static_cast<unsigned long long>(totals.bytes),
              static_cast<unsigned long long>(totals.errors));
  return 0;
}
