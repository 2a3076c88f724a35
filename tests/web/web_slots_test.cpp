// Connection slots held without a token (docs/security.md): WebSockets that
// never read, and one address holding every slot, must not starve /healthz.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "tests/web/fake_daemon_api.h"
#include "tests/web/http_client.h"
#include "web/server/web_server.h"

namespace xr::web::test {
namespace {

// A WebSocket client that upgrades and then never reads a frame.
struct SilentWs {
  explicit SilentWs(std::uint16_t port, int rcvbuf = 0) : ws(ioc) {
    auto& sock = beast::get_lowest_layer(ws).socket();
    sock.open(tcp::v4());
    if (rcvbuf > 0) sock.set_option(asio::socket_base::receive_buffer_size(rcvbuf));
    beast::get_lowest_layer(ws).expires_after(kSafetyNet);
    beast::get_lowest_layer(ws).connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
    beast::error_code ec;
    ws.handshake(res, "127.0.0.1:" + std::to_string(port), "/ws", ec);
    accepted = !ec;
  }
  asio::io_context ioc;
  websocket::stream<beast::tcp_stream> ws;
  websocket::response_type res;
  bool accepted = false;
};

class SlotsTest : public ::testing::Test {
 protected:
  void start(WebServerOptions o) {
    o.listen = "127.0.0.1";
    o.port = 0;
    o.token = "slots-test-token-0123456789";
    o.telemetry_rate_hz = 20;
    server_ = std::make_unique<WebServer>(api_, o);
    server_->start();
    port_ = server_->port();
  }
  // Waits (bounded by the safety net, never asserting on time) for cond.
  template <class F>
  bool waitFor(F cond) {
    const auto end = std::chrono::steady_clock::now() + kSafetyNet;
    while (!cond()) {
      if (std::chrono::steady_clock::now() > end) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
  }
  FakeDaemonApi api_;
  std::unique_ptr<WebServer> server_;
  std::uint16_t port_ = 0;
};

TEST_F(SlotsTest, SixtyFourSilentWebSocketsDoNotStarveHealthz) {
  api_.publish();
  WebServerOptions o;
  o.max_connections = 64;
  start(o);
  std::vector<std::unique_ptr<SilentWs>> clients;
  int accepted = 0;
  for (int i = 0; i < 64; ++i) {
    clients.push_back(std::make_unique<SilentWs>(port_));
    accepted += clients.back()->accepted;
  }
  // One address gets a quarter of the slots for WebSockets.
  EXPECT_EQ(accepted, 16);
  int healthy = 0;
  for (int i = 0; i < 45; ++i) healthy += httpRequest(port_, bhttp::verb::get, "/healthz").status == 200;
  EXPECT_EQ(healthy, 45);
}

TEST_F(SlotsTest, WebSocketsTogetherLeaveSlotsForRequests) {
  api_.publish();
  WebServerOptions o;
  o.max_connections = 16;
  o.max_ws_per_ip = 100;  // only the overall WebSocket share applies here
  o.max_per_ip = 100;
  start(o);
  std::vector<std::unique_ptr<SilentWs>> clients;
  int accepted = 0;
  for (int i = 0; i < 16; ++i) {
    clients.push_back(std::make_unique<SilentWs>(port_));
    accepted += clients.back()->accepted;
  }
  EXPECT_EQ(accepted, 14);  // 16 - 16/8
  EXPECT_EQ(httpRequest(port_, bhttp::verb::get, "/healthz").status, 200);
}

TEST_F(SlotsTest, OneAddressHoldsAtMostItsShareOfConnections) {
  WebServerOptions o;
  o.max_connections = 64;
  o.max_per_ip = 4;
  start(o);
  asio::io_context ioc;
  std::vector<tcp::socket> idle;
  for (int i = 0; i < 3; ++i) {
    idle.emplace_back(ioc);
    idle.back().connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port_));
  }
  ASSERT_TRUE(waitFor([&] { return server_->stats().connections == 3; }));
  // The 4th connection of this address is still served...
  EXPECT_EQ(httpRequest(port_, bhttp::verb::get, "/healthz").status, 200);
  ASSERT_TRUE(waitFor([&] { return server_->stats().connections == 3; }));
  idle.emplace_back(ioc);
  idle.back().connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port_));
  ASSERT_TRUE(waitFor([&] { return server_->stats().connections == 4; }));
  // ...the 5th is refused.
  const auto r = rawExchange(port_, "GET /healthz HTTP/1.1\r\nHost: localhost\r\n\r\n");
  EXPECT_EQ(r.substr(0, 12), "HTTP/1.1 503");
  idle.clear();
  ASSERT_TRUE(waitFor([&] { return server_->stats().connections == 0; }));
  EXPECT_EQ(httpRequest(port_, bhttp::verb::get, "/healthz").status, 200);
}

// A client that sends half a request from `from` and then waits.
struct SlowRequest {
  SlowRequest(asio::io_context& ioc, std::uint16_t port, const std::string& from) : sock(ioc) {
    sock.open(tcp::v4());
    sock.bind(tcp::endpoint(asio::ip::make_address(from), 0));
    sock.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
    asio::write(sock, asio::buffer(std::string("GET /api/status HTTP/1.1\r\nHost: localhost\r\nX-Slow: ")));
  }
  tcp::socket sock;
};

TEST_F(SlotsTest, SixtyFourSlowRequestsFromEightAddressesDoNotStarveHealthz) {
  WebServerOptions o;
  o.max_connections = 64;
  o.evict_waiting_after = std::chrono::milliseconds(0);  // what the default 2 s is for: here at once
  start(o);
  asio::io_context ioc;
  std::vector<std::unique_ptr<SlowRequest>> slow;
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 8; ++i)
      slow.push_back(std::make_unique<SlowRequest>(ioc, port_, "127.0.0." + std::to_string(a + 2)));
  ASSERT_TRUE(waitFor([&] { return server_->stats().connections == 64; }));
  // Every slot is held by a request that never ends; each health check
  // closes the one that has waited longest.
  int healthy = 0;
  for (int i = 0; i < 20; ++i) healthy += httpRequest(port_, bhttp::verb::get, "/healthz").status == 200;
  EXPECT_EQ(healthy, 20);
  EXPECT_GE(server_->stats().connections_evicted, 1u);  // a slot freed is reused by the next check
  EXPECT_EQ(server_->stats().connections_refused, 0u);
}

TEST_F(SlotsTest, ARequestWaitingLessThanTheGraceIsNotClosed) {
  WebServerOptions o;
  o.max_connections = 2;
  o.max_per_ip = 100;
  o.evict_waiting_after = std::chrono::hours(1);
  start(o);
  asio::io_context ioc;
  SlowRequest a(ioc, port_, "127.0.0.2"), b(ioc, port_, "127.0.0.3");
  ASSERT_TRUE(waitFor([&] { return server_->stats().connections == 2; }));
  const auto r = rawExchange(port_, "GET /healthz HTTP/1.1\r\nHost: localhost\r\n\r\n");
  EXPECT_EQ(r.substr(0, 12), "HTTP/1.1 503");
  EXPECT_EQ(server_->stats().connections_evicted, 0u);
}

TEST_F(SlotsTest, AWebSocketThatNeverReadsIsClosed) {
  api_.publish();
  WebServerOptions o;
  o.ws_send_buffer = 2048;
  o.ws_write_timeout = std::chrono::milliseconds(200);
  start(o);
  SilentWs silent(port_, 2048);
  ASSERT_TRUE(silent.accepted);
  ASSERT_TRUE(waitFor([&] { return server_->stats().ws_clients == 1; }));
  // New telemetry keeps coming; once the buffers are full the frame waits
  // past ws_write_timeout and the server closes the client.
  std::atomic<bool> stop{false};
  std::thread publisher([&] {
    while (!stop) {
      api_.publish();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  const bool closed = waitFor([&] { return server_->stats().ws_clients == 0; });
  stop = true;
  publisher.join();
  EXPECT_TRUE(closed);
  EXPECT_EQ(server_->stats().connections, 0u);
}

}  // namespace
}  // namespace xr::web::test
