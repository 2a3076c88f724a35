// Pairing without a terminal (docs/security.md "Pairing without a
// terminal"): on a new regulator with nothing paired, the first device pairs
// without a code for 15 minutes of elapsed time and becomes the owner; the
// window closes at that pairing and never opens while a device is paired.
#include <gtest/gtest.h>

#include <boost/json.hpp>

#include "tests/web/fake_daemon_api.h"
#include "tests/web/http_client.h"
#include "web/server/api_handler.h"
#include "web/server/on_board.h"
#include "web/server/pairing.h"
#include "web/server/web_server.h"

namespace xr::web::test {
namespace {
namespace json = boost::json;

constexpr std::int64_t kWindowMs = 15 * 60 * 1000;

struct WindowFixture : ::testing::Test {
  std::int64_t wallMs = 1'700'000'000'000;
  std::int64_t elapsedMs = 1'000;
  std::shared_ptr<MemoryAuthStore> store = std::make_shared<MemoryAuthStore>();
  Pairing pairing{store, [this] { return wallMs; }, [this] { return elapsedMs; }};
};

TEST_F(WindowFixture, TheFirstDevicePairsWithoutACodeAndIsTheOwner) {
  EXPECT_EQ(pairing.pairInWindow("phone").kind, Pairing::Outcome::NoWindow);  // not opened: a code is needed
  pairing.openFirstStartWindow(kWindowMs);
  EXPECT_TRUE(pairing.window().open);
  EXPECT_EQ(pairing.window().closesInMs, kWindowMs);
  const auto r = pairing.pairInWindow("Skipper's phone");
  ASSERT_EQ(r.kind, Pairing::Outcome::Paired);
  EXPECT_TRUE(pairing.isDeviceToken(r.token));
  EXPECT_EQ(pairing.ownerId(), r.device.id);
}

TEST_F(WindowFixture, TheWindowClosesAtTheFirstPairing) {
  pairing.openFirstStartWindow(kWindowMs);
  const auto first = pairing.pairInWindow("first", "192.168.4.20");
  ASSERT_EQ(first.kind, Pairing::Outcome::Paired);
  EXPECT_FALSE(pairing.window().open);
  // The second device is told the window was used, and by whom (before: "no
  // pairing window is open", as if it had never opened).
  const auto second = pairing.pairInWindow("second");
  EXPECT_EQ(second.kind, Pairing::Outcome::WindowClaimed);
  EXPECT_EQ(second.claimedBy, "device \"first\" (" + first.device.id + ") from 192.168.4.20");
  EXPECT_EQ(pairing.windowClaim(), second.claimedBy);
  // Once the window would have closed anyway, it is just closed.
  elapsedMs += kWindowMs;
  EXPECT_EQ(pairing.pairInWindow("third").kind, Pairing::Outcome::NoWindow);
}

TEST_F(WindowFixture, TheWindowEndsAfterFifteenMinutesOfElapsedTimeWhateverTheWallClock) {
  pairing.openFirstStartWindow(kWindowMs);
  wallMs -= 6 * 3'600'000;  // a GPS fix sets the clock 6 h back
  elapsedMs += kWindowMs - 1;
  EXPECT_TRUE(pairing.window().open);
  elapsedMs += 1;
  EXPECT_FALSE(pairing.window().open);
  EXPECT_EQ(pairing.pairInWindow("late").kind, Pairing::Outcome::NoWindow);
}

TEST_F(WindowFixture, TheWindowNeverOpensWhileADeviceIsPaired) {
  ASSERT_EQ(pairing.pair(pairing.newCode().code, "owner").kind, Pairing::Outcome::Paired);
  pairing.openFirstStartWindow(kWindowMs);
  EXPECT_FALSE(pairing.window().open);
  EXPECT_EQ(pairing.pairInWindow("stranger").kind, Pairing::Outcome::NoWindow);
}

TEST_F(WindowFixture, APairingByCodeClosesTheWindow) {
  pairing.openFirstStartWindow(kWindowMs);
  ASSERT_EQ(pairing.pair(pairing.newCode().code, "owner").kind, Pairing::Outcome::Paired);
  EXPECT_EQ(pairing.pairInWindow("stranger").kind, Pairing::Outcome::NoWindow);
}

TEST(PairingWindowServer, ANewPhonePairsWithoutACodeOnlyInTheWindow) {
  FakeDaemonApi api;
  WebServerOptions o;
  o.listen = "127.0.0.1";
  o.port = 0;
  o.token = "installer-token-0123456789abcdef";
  WebServer server(api, o);
  server.start();
  const auto post = [&](const std::string& body) {
    return httpRequest(server.port(), bhttp::verb::post, "/api/pair", body);
  };
  const auto windowOpen = [&] {
    const auto r = httpRequest(server.port(), bhttp::verb::get, "/api/pair/window");
    EXPECT_EQ(r.status, 200) << r.body;
    return json::parse(r.body).at("open").as_bool();
  };
  EXPECT_FALSE(windowOpen());
  EXPECT_EQ(post(R"({"name": "phone"})").status, 403);
  server.openFirstStartPairingWindow(kWindowMs);
  EXPECT_TRUE(windowOpen());
  const auto r = post(R"({"name": "Skipper phone"})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_FALSE(json::parse(r.body).at("token").as_string().empty());
  EXPECT_FALSE(windowOpen());
  const auto late = post(R"({"name": "stranger"})");
  EXPECT_EQ(late.status, 403);
  EXPECT_NE(late.body.find("already used by device \\\"Skipper phone\\\""), std::string::npos) << late.body;
  const auto ev = api.securityEvents();
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_NE(ev[0].find("Paired device \"Skipper phone\""), std::string::npos) << ev[0];
  EXPECT_NE(ev[0].find("as the owner without a code, in a pairing window from 127.0.0.1"), std::string::npos)
      << ev[0];
  EXPECT_NE(ev[1].find("Refused a pairing without a code of \"stranger\" from 127.0.0.1"), std::string::npos)
      << ev[1];
}

namespace ip = boost::asio::ip;

TEST(OnBoard, LoopbackLinkLocalAndTheBoardsSubnetsAreOnBoard) {
  const std::vector<BoardSubnet> nets = {{"wlan0", ip::make_address("192.168.4.1"), 24},
                                         {"eth0", ip::make_address("2001:db8:1::10"), 64}};
  for (const char* a : {"127.0.0.1", "127.8.9.10", "::1", "169.254.7.7", "fe80::1234", "192.168.4.200",
                        "192.168.4.0", "::ffff:192.168.4.20", "2001:db8:1::99"})
    EXPECT_TRUE(onBoard(ip::make_address(a), nets)) << a;
  // A marina's network routed to the boat's, the next subnet up, a public
  // address, another IPv6 prefix.
  for (const char* a : {"192.168.5.20", "192.168.3.255", "10.0.0.7", "203.0.113.5", "::ffff:203.0.113.5",
                        "2001:db8:2::99", "169.253.1.1"})
    EXPECT_FALSE(onBoard(ip::make_address(a), nets)) << a;
  EXPECT_FALSE(onBoard(ip::make_address("192.168.4.20"), {}));  // no subnets known: loopback only
  EXPECT_EQ(subnetsText(nets), "wlan0 192.168.4.1/24, eth0 2001:db8:1::10/64");
  EXPECT_EQ(subnetsText({}), "none");
}

TEST(OnBoard, AddressesAreWrittenWithBracketsAroundIpv6) {
  EXPECT_EQ(addressText(ip::make_address("::1")), "[::1]");
  EXPECT_EQ(addressText(ip::make_address("192.168.4.20")), "192.168.4.20");
  EXPECT_EQ(hostPortText("::1", 8080), "[::1]:8080");
  EXPECT_EQ(hostPortText("::", 8080), "[::]:8080");
  EXPECT_EQ(hostPortText("0.0.0.0", 8080), "0.0.0.0:8080");
  EXPECT_EQ(hostPortText("[::1]", 8080), "[::1]:8080");
}

TEST(OnBoard, TheBoardsOwnSubnetsAreFoundAndLoopbackIsLeftOut) {
  for (const auto& s : boardSubnets()) {
    EXPECT_FALSE(s.address.is_loopback()) << s.interface;
    EXPECT_TRUE(onBoard(s.address, {s})) << s.interface;
  }
}

// The reproducer: with listen = "0.0.0.0", a device on another network that
// reached the port in the first 15 minutes became the owner with no code.
TEST(PairingWindowServer, ADeviceOffTheBoatsNetworksIsRefusedTheNoCodeWindow) {
  FakeDaemonApi api;
  WebServerOptions o;
  o.token = "installer-token-0123456789abcdef";
  ApiHandler handler(api, o);
  handler.pairing().openFirstStartWindow(kWindowMs);
  Request req{bhttp::verb::post, "/api/pair", 11};
  req.set(bhttp::field::content_type, "application/json");
  req.body() = R"({"name": "stranger"})";
  req.prepare_payload();
  for (const char* from : {"203.0.113.5", "198.51.100.7", "::ffff:203.0.113.5"}) {
    const auto r = handler.handle(req, ip::make_address(from));
    EXPECT_EQ(r.result_int(), 403) << from;
    EXPECT_NE(r.body().find("only for a device on the boat's own network"), std::string::npos) << r.body();
  }
  EXPECT_EQ(handler.handle(req).result_int(), 403) << "no address known: not on board";
  EXPECT_TRUE(handler.pairing().window().open) << "the window is still the owner's";
  EXPECT_TRUE(handler.pairing().devices().empty());
  ASSERT_FALSE(api.securityEvents().empty());
  EXPECT_NE(api.securityEvents()[0].find("Refused a pairing without a code from 203.0.113.5"),
            std::string::npos);
  // The owner, on board (here: this machine), pairs; a second device on
  // board is told who claimed the window, and the owner's list says it too.
  req.body() = R"({"name": "Skipper phone"})";
  req.prepare_payload();
  const auto owner = handler.handle(req, ip::make_address("::1"));
  ASSERT_EQ(owner.result_int(), 200) << owner.body();
  req.body() = R"({"name": "late phone"})";
  req.prepare_payload();
  const auto late = handler.handle(req, ip::make_address("127.0.0.1"));
  EXPECT_EQ(late.result_int(), 403);
  EXPECT_NE(late.body().find("already used by device \\\"Skipper phone\\\""), std::string::npos)
      << late.body();
  EXPECT_NE(late.body().find("from [::1]"), std::string::npos) << late.body();
  const auto stranger = handler.handle(req, ip::make_address("203.0.113.5"));
  EXPECT_EQ(stranger.result_int(), 403);
  EXPECT_EQ(stranger.body().find("Skipper"), std::string::npos)
      << "a stranger learns nothing: " << stranger.body();
  bool ownerEvent = false, lateEvent = false;
  for (const auto& e : api.securityEvents()) {
    ownerEvent |= e.find("as the owner without a code, in a pairing window from [::1]") != std::string::npos;
    lateEvent |=
        e.find("Refused a pairing without a code of \"late phone\" from 127.0.0.1") != std::string::npos;
  }
  EXPECT_TRUE(ownerEvent);
  EXPECT_TRUE(lateEvent);
  Request list{bhttp::verb::get, "/api/pair/devices", 11};
  list.set(bhttp::field::authorization, "Bearer " + o.token);
  const auto devices = json::parse(handler.handle(list).body());
  EXPECT_NE(std::string(devices.at("window_claimed_by").as_string()).find("Skipper phone"),
            std::string::npos);
}

}  // namespace
}  // namespace xr::web::test
