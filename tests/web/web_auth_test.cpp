// Getting in (docs/security.md "Pairing"): pairing codes, per-device
// write tokens, reads vs writes, the Host and Origin checks against DNS
// rebinding. Pairing logic with an injected clock, then through a real
// server on a loopback port.
#include <gtest/gtest.h>

#include <boost/json.hpp>

#include "tests/web/fake_daemon_api.h"
#include "tests/web/http_client.h"
#include "web/server/pairing.h"
#include "web/server/request_checks.h"
#include "web/server/web_server.h"

namespace xr::web::test {
namespace {
namespace json = boost::json;

// ---------------------------------------------------------------- Pairing

struct PairingFixture : ::testing::Test {
  std::int64_t nowMs = 1'700'000'000'000;
  std::shared_ptr<MemoryAuthStore> store = std::make_shared<MemoryAuthStore>();
  Pairing pairing{store, [this] { return nowMs; }};
  static std::string wrongCode(const std::string& right) { return right == "000000" ? "000001" : "000000"; }
};

TEST_F(PairingFixture, CodeIsSixDigitsAndPairsOnce) {
  const auto c = pairing.newCode();
  ASSERT_EQ(c.code.size(), 6u);
  EXPECT_EQ(c.code.find_first_not_of("0123456789"), std::string::npos);
  EXPECT_EQ(c.expiresMs, nowMs + kCodeLifetimeMs);
  const auto r = pairing.pair(c.code, "Anna's phone");
  ASSERT_EQ(r.kind, Pairing::Outcome::Paired);
  EXPECT_EQ(r.token.size(), 64u);
  EXPECT_EQ(r.device.name, "Anna's phone");
  EXPECT_TRUE(pairing.isDeviceToken(r.token));
  EXPECT_FALSE(pairing.isDeviceToken(r.token.substr(1)));
  // Single use: the same code again is a wrong code.
  EXPECT_EQ(pairing.pair(c.code, "again").kind, Pairing::Outcome::WrongCode);
}

TEST_F(PairingFixture, OnlyTheHashIsStoredAndSurvivesARestart) {
  const auto r = pairing.pair(pairing.newCode().code, "");
  ASSERT_EQ(r.kind, Pairing::Outcome::Paired);
  const auto saved = store->loadDevices();
  ASSERT_EQ(saved.size(), 1u);
  EXPECT_EQ(saved[0].hash, sha256Hex(r.token));
  EXPECT_NE(saved[0].hash, r.token);
  EXPECT_EQ(saved[0].name, "device");
  Pairing restarted{store, [this] { return nowMs; }};
  EXPECT_TRUE(restarted.isDeviceToken(r.token));
}

TEST_F(PairingFixture, CodeExpiresAtItsLifetime) {
  const auto c = pairing.newCode();
  nowMs += kCodeLifetimeMs - 1;
  const auto justBefore = pairing.pair(c.code, "");
  EXPECT_EQ(justBefore.kind, Pairing::Outcome::Paired);
  const auto c2 = pairing.newCode();
  nowMs += kCodeLifetimeMs;
  EXPECT_EQ(pairing.pair(c2.code, "").kind, Pairing::Outcome::WrongCode);
}

TEST_F(PairingFixture, FourWrongTriesStillLetTheRightCodeIn) {
  const auto c = pairing.newCode();
  for (int i = 0; i < kMaxWrongTries - 1; ++i) {
    const auto r = pairing.pair(wrongCode(c.code), "");
    ASSERT_EQ(r.kind, Pairing::Outcome::WrongCode);
    EXPECT_EQ(r.triesLeft, kMaxWrongTries - 1 - i);
  }
  EXPECT_EQ(pairing.pair(c.code, "").kind, Pairing::Outcome::Paired);
}

TEST_F(PairingFixture, FifthWrongTryBurnsTheCodeAndLocksOut) {
  const auto c = pairing.newCode();
  for (int i = 0; i < kMaxWrongTries - 1; ++i) pairing.pair(wrongCode(c.code), "");
  const auto fifth = pairing.pair(wrongCode(c.code), "");
  ASSERT_EQ(fifth.kind, Pairing::Outcome::LockedOut);
  EXPECT_EQ(fifth.retryAfterMs, kLockoutMs);
  // Locked: even the right code is not looked at.
  nowMs += kLockoutMs - 1;
  EXPECT_EQ(pairing.pair(c.code, "").kind, Pairing::Outcome::LockedOut);
  // After the lock-out the burnt code is still void.
  nowMs += 1;
  EXPECT_EQ(pairing.pair(c.code, "").kind, Pairing::Outcome::WrongCode);
  EXPECT_TRUE(pairing.devices().empty());
  // A new code from the owner ends the lock-out at once.
  for (int i = 0; i < kMaxWrongTries; ++i) pairing.pair("x", "");
  EXPECT_EQ(pairing.pair(c.code, "").kind, Pairing::Outcome::LockedOut);
  EXPECT_EQ(pairing.pair(pairing.newCode().code, "").kind, Pairing::Outcome::Paired);
}

TEST_F(PairingFixture, WithoutACodeNothingPairs) {
  EXPECT_EQ(pairing.pair("", "").kind, Pairing::Outcome::WrongCode);
  EXPECT_EQ(pairing.pair("123456", "").kind, Pairing::Outcome::WrongCode);
}

TEST_F(PairingFixture, RevokeOneAndAll) {
  const auto a = pairing.pair(pairing.newCode().code, "a");
  const auto b = pairing.pair(pairing.newCode().code, "b");
  const auto c = pairing.pair(pairing.newCode().code, "c");
  ASSERT_EQ(pairing.devices().size(), 3u);
  const Pairing::Caller installer{true, ""};
  EXPECT_EQ(pairing.revoke(a.device.id, installer), Pairing::Revoke::Revoked);
  EXPECT_EQ(pairing.revoke(a.device.id, installer), Pairing::Revoke::NoSuchDevice);
  EXPECT_FALSE(pairing.isDeviceToken(a.token));
  EXPECT_TRUE(pairing.isDeviceToken(b.token));
  EXPECT_EQ(store->loadDevices().size(), 2u);
  EXPECT_EQ(pairing.revokeAll(installer).revoked, 2u);
  EXPECT_FALSE(pairing.isDeviceToken(c.token));
  EXPECT_TRUE(store->loadDevices().empty());
}

TEST_F(PairingFixture, DeviceCountIsBounded) {
  for (std::size_t i = 0; i < kMaxPairedDevices; ++i)
    ASSERT_EQ(pairing.pair(pairing.newCode().code, "").kind, Pairing::Outcome::Paired);
  EXPECT_EQ(pairing.pair(pairing.newCode().code, "").kind, Pairing::Outcome::Full);
}

TEST(Pairing, DeviceNamesArePrintableAndShort) {
  EXPECT_EQ(cleanDeviceName("a\"b\\c\nd"), "abcd");
  EXPECT_EQ(cleanDeviceName(std::string(100, 'x')).size(), kMaxDeviceNameLength);
  EXPECT_EQ(cleanDeviceName("\x01\x02"), "device");
}

TEST(Pairing, Sha256KnownAnswer) {
  // FIPS 180-2 test vector "abc".
  EXPECT_EQ(sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

// ---------------------------------------------------------------- Host / Origin

TEST(RequestChecks, AnEmptyMissingOrRepeatedHostIsABadRequest) {
  EXPECT_EQ(hostHeaderProblem(1, "", 11), "empty Host header");
  EXPECT_EQ(hostHeaderProblem(1, "  ", 10), "empty Host header");
  EXPECT_EQ(hostHeaderProblem(0, "", 11), "no Host header");
  EXPECT_EQ(hostHeaderProblem(2, "boat", 11), "more than one Host header");
  EXPECT_EQ(hostHeaderProblem(0, "", 10), "");  // HTTP/1.0 tools send none
  EXPECT_EQ(hostHeaderProblem(1, "boat:8080", 11), "");
}

TEST(RequestChecks, HostNamesThisMachineAnswersTo) {
  const std::vector<std::string> none;
  EXPECT_TRUE(hostAllowed("", none, "boat"));
  EXPECT_TRUE(hostAllowed("192.168.4.1:8080", none, "boat"));
  EXPECT_TRUE(hostAllowed("[fe80::1]:8080", none, "boat"));
  EXPECT_TRUE(hostAllowed("localhost:8080", none, "boat"));
  EXPECT_TRUE(hostAllowed("boat:8080", none, "boat"));
  EXPECT_TRUE(hostAllowed("BOAT.local", none, "boat"));
  EXPECT_TRUE(hostAllowed("boat.local.", none, "boat"));
  EXPECT_TRUE(hostAllowed("boat", none, "boat.example.org"));
  EXPECT_FALSE(hostAllowed("evil.example:8080", none, "boat"));
  EXPECT_FALSE(hostAllowed("boat.evil.example", none, "boat"));
  EXPECT_FALSE(hostAllowed("boatx.local", none, "boat"));
  EXPECT_FALSE(hostAllowed("[fe80::1", none, "boat"));
  EXPECT_TRUE(hostAllowed("regulator.home:8080", {"regulator.home"}, "boat"));
}

TEST(RequestChecks, OriginNeedsAnHttpSchemeAndTheSameHost) {
  const std::vector<std::string> none;
  EXPECT_TRUE(originAllowed("", "boat:8080", none));
  EXPECT_TRUE(originAllowed("http://boat:8080", "boat:8080", none));
  EXPECT_TRUE(originAllowed("https://boat:8080", "boat:8080", none));
  EXPECT_FALSE(originAllowed("ftp://boat:8080", "boat:8080", none));
  EXPECT_FALSE(originAllowed("boat:8080", "boat:8080", none));
  EXPECT_FALSE(originAllowed("null", "boat:8080", none));
  EXPECT_FALSE(originAllowed("http://evil.example", "boat:8080", none));
  EXPECT_FALSE(originAllowed("http://boat:8080", "", none));
  EXPECT_TRUE(originAllowed("http://chartplotter:3000", "boat:8080", {"http://chartplotter:3000"}));
}

// ---------------------------------------------------------------- through the server

constexpr const char* kToken = "static-token-for-installers";

class AuthServerTest : public ::testing::Test {
 protected:
  void start(bool readsNeedToken = false) {
    WebServerOptions o;
    o.listen = "127.0.0.1";
    o.port = 0;
    o.token = kToken;
    o.reads_require_token = readsNeedToken;
    o.auth_store = store_;
    server_ = std::make_unique<WebServer>(api_, o);
    server_->start();
    port_ = server_->port();
  }
  HttpResult req(bhttp::verb m, const std::string& target, const std::string& body = "",
                 std::map<std::string, std::string> h = {}) {
    return httpRequest(port_, m, target, body, h);
  }
  static std::map<std::string, std::string> bearer(const std::string& t) {
    return {{"Authorization", "Bearer " + t}};
  }
  HttpResult patchWith(const std::string& token) {
    return req(bhttp::verb::patch, "/api/params", R"({"BulkVoltage": 14.3})", bearer(token));
  }
  std::string pairNewDevice(const std::string& name) {
    const auto code = server_->newPairingCode().code;
    const auto r =
        req(bhttp::verb::post, "/api/pair", R"({"code": ")" + code + R"(", "name": ")" + name + "\"}");
    EXPECT_EQ(r.status, 200) << r.body;
    return std::string(json::parse(r.body).at("token").as_string());
  }

  FakeDaemonApi api_;
  std::shared_ptr<MemoryAuthStore> store_ = std::make_shared<MemoryAuthStore>();
  std::unique_ptr<WebServer> server_;
  std::uint16_t port_ = 0;
};

TEST_F(AuthServerTest, APairedPhoneWritesAndAStrangerDoesNot) {
  start();
  EXPECT_EQ(req(bhttp::verb::patch, "/api/params", R"({"BulkVoltage": 14.3})").status, 401);
  EXPECT_EQ(patchWith("").status, 403);
  EXPECT_EQ(patchWith("0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef").status, 403);
  const std::string token = pairNewDevice("phone");
  EXPECT_EQ(patchWith(token).status, 200);
  const auto cmd = req(bhttp::verb::post, "/api/commands", R"({"command": "auto"})", bearer(token));
  EXPECT_NE(cmd.status, 401);
  EXPECT_NE(cmd.status, 403);
  // The installers' static token keeps working.
  EXPECT_EQ(patchWith(kToken).status, 200);
}

// the daemon's settings-change event names who asked.
TEST_F(AuthServerTest, APatchTellsTheDaemonWhichDeviceSentIt) {
  start();
  const std::string token = pairNewDevice("Anna's phone");
  ASSERT_EQ(patchWith(token).status, 200);
  EXPECT_EQ(api_.lastPatchSource(), "device \"Anna's phone\"");
  ASSERT_EQ(patchWith(kToken).status, 200);
  EXPECT_EQ(api_.lastPatchSource(), "the installer token");
}

TEST_F(AuthServerTest, WritesNeverTakeATokenFromTheUrl) {
  start();
  const std::string token = pairNewDevice("phone");
  for (const std::string& t : {std::string(kToken), token}) {
    const auto r = req(bhttp::verb::patch, "/api/params?token=" + t, R"({"BulkVoltage": 14.3})");
    EXPECT_EQ(r.status, 401) << t;
    EXPECT_EQ(req(bhttp::verb::post, "/api/commands?token=" + t, R"({"command": "auto"})").status, 401);
  }
}

TEST_F(AuthServerTest, ReadsAreOpenUnlessConfiguredAndThenTakeDeviceTokens) {
  start(false);
  EXPECT_EQ(req(bhttp::verb::get, "/api/params").status, 200);
  server_.reset();
  start(true);
  EXPECT_EQ(req(bhttp::verb::get, "/api/params").status, 401);
  const std::string token = pairNewDevice("phone");
  EXPECT_EQ(req(bhttp::verb::get, "/api/params", "", bearer(token)).status, 200);
  EXPECT_EQ(req(bhttp::verb::get, "/api/params?token=" + token).status, 200);  // /ws from a browser
  EXPECT_EQ(req(bhttp::verb::get, "/api/params?token=" + token + "x").status, 403);
}

TEST_F(AuthServerTest, PairAnswersWrongCodeThenLocksOut) {
  start();
  const auto code = server_->newPairingCode().code;
  const std::string wrong = code == "000000" ? "000001" : "000000";
  for (int i = 1; i < kMaxWrongTries; ++i) {
    const auto r = req(bhttp::verb::post, "/api/pair", R"({"code": ")" + wrong + "\"}");
    ASSERT_EQ(r.status, 403);
    EXPECT_EQ(json::parse(r.body).at("tries_left").as_int64(), kMaxWrongTries - i);
  }
  const auto locked = req(bhttp::verb::post, "/api/pair", R"({"code": ")" + wrong + "\"}");
  EXPECT_EQ(locked.status, 429);
  EXPECT_EQ(locked.headers["Retry-After"], std::to_string(kLockoutMs / 1000));
  EXPECT_EQ(req(bhttp::verb::post, "/api/pair", R"({"code": ")" + code + "\"}").status, 429);
  EXPECT_EQ(req(bhttp::verb::post, "/api/pair", "not json").status, 400);
  EXPECT_EQ(req(bhttp::verb::get, "/api/pair").status, 405);
}

TEST_F(AuthServerTest, APairedDeviceMakesCodesListsAndRevokes) {
  start();
  EXPECT_EQ(req(bhttp::verb::post, "/api/pair/code").status, 401);
  EXPECT_EQ(req(bhttp::verb::get, "/api/pair/devices").status, 401);
  EXPECT_EQ(req(bhttp::verb::delete_, "/api/pair/devices").status, 401);
  const std::string owner = pairNewDevice("owner");
  const auto codeReply = req(bhttp::verb::post, "/api/pair/code", "", bearer(owner));
  ASSERT_EQ(codeReply.status, 200);
  const auto code = std::string(json::parse(codeReply.body).at("code").as_string());
  EXPECT_EQ(json::parse(codeReply.body).at("expires_in_s").as_int64(), kCodeLifetimeMs / 1000);
  const auto guest = req(bhttp::verb::post, "/api/pair", R"({"code": ")" + code + R"(", "name": "guest"})");
  ASSERT_EQ(guest.status, 200);
  const auto guestToken = std::string(json::parse(guest.body).at("token").as_string());
  const auto guestId = std::string(json::parse(guest.body).at("id").as_string());

  const auto list = req(bhttp::verb::get, "/api/pair/devices", "", bearer(kToken));
  ASSERT_EQ(list.status, 200);
  const json::value listed = json::parse(list.body);
  ASSERT_EQ(listed.at("devices").as_array().size(), 2u);
  EXPECT_EQ(list.body.find(guestToken), std::string::npos);  // tokens are never listed

  EXPECT_EQ(req(bhttp::verb::delete_, "/api/pair/devices/" + guestId, "", bearer(owner)).status, 200);
  EXPECT_EQ(patchWith(guestToken).status, 403);
  EXPECT_EQ(patchWith(owner).status, 200);
  EXPECT_EQ(req(bhttp::verb::delete_, "/api/pair/devices/" + guestId, "", bearer(owner)).status, 404);
  const auto all = req(bhttp::verb::delete_, "/api/pair/devices", "", bearer(kToken));
  EXPECT_EQ(json::parse(all.body).at("revoked").as_int64(), 1);
  EXPECT_EQ(patchWith(owner).status, 403);
  EXPECT_EQ(patchWith(kToken).status, 200);  // revoke all never locks the installer out
}

TEST_F(AuthServerTest, ARequestForAnotherHostIsRefused) {
  start();
  EXPECT_EQ(
      req(bhttp::verb::get, "/api/params", "", {{"Host", "evil.example:" + std::to_string(port_)}}).status,
      421);
  EXPECT_EQ(req(bhttp::verb::get, "/api/params", "", {{"Host", "localhost:" + std::to_string(port_)}}).status,
            200);
  EXPECT_EQ(req(bhttp::verb::get, "/api/params").status, 200);
}

TEST_F(AuthServerTest, AWriteFromAPageElsewhereIsRefused) {
  start();
  const std::string self = "http://127.0.0.1:" + std::to_string(port_);
  auto h = bearer(kToken);
  h["Origin"] = "http://evil.example";
  EXPECT_EQ(req(bhttp::verb::patch, "/api/params", R"({"BulkVoltage": 14.3})", h).status, 403);
  EXPECT_EQ(req(bhttp::verb::post, "/api/pair", R"({"code": "123456"})", {{"Origin", "http://evil.example"}})
                .status,
            403);
  h["Origin"] = "ftp://127.0.0.1:" + std::to_string(port_);
  EXPECT_EQ(req(bhttp::verb::patch, "/api/params", R"({"BulkVoltage": 14.3})", h).status, 403);
  h["Origin"] = self;
  EXPECT_EQ(req(bhttp::verb::patch, "/api/params", R"({"BulkVoltage": 14.3})", h).status, 200);
  EXPECT_EQ(wsUpgradeStatus(port_, "/ws", "ftp://127.0.0.1:" + std::to_string(port_)), 403);
}

}  // namespace
}  // namespace xr::web::test
