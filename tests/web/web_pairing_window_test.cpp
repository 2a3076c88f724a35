// Pairing without a terminal (docs/security.md "Pairing without a
// terminal"): on a new regulator with nothing paired, the first device pairs
// without a code for 15 minutes of elapsed time and becomes the owner; the
// window closes at that pairing and never opens while a device is paired.
#include <gtest/gtest.h>

#include <boost/json.hpp>

#include "tests/web/fake_daemon_api.h"
#include "tests/web/http_client.h"
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
  ASSERT_EQ(pairing.pairInWindow("first").kind, Pairing::Outcome::Paired);
  EXPECT_FALSE(pairing.window().open);
  EXPECT_EQ(pairing.pairInWindow("second").kind, Pairing::Outcome::NoWindow);
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
  EXPECT_EQ(post(R"({"name": "stranger"})").status, 403);
  const auto ev = api.securityEvents();
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_NE(ev[0].find("Paired device \"Skipper phone\""), std::string::npos) << ev[0];
  EXPECT_NE(ev[0].find("as the owner without a code, in a pairing window"), std::string::npos) << ev[0];
}

}  // namespace
}  // namespace xr::web::test
