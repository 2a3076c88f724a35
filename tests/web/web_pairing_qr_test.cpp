// The QR code a paired phone shows for the next one (docs/security.md
// "Pairing without a terminal"): only a paired device or the installer token
// makes one; it pairs one device, once, within 10 minutes; it names who made
// it in the pairing's event; a wrong one counts as a wrong code.
#include <gtest/gtest.h>

#include <boost/json.hpp>

#include "tests/web/fake_daemon_api.h"
#include "web/server/api_handler.h"
#include "web/server/pairing.h"

namespace xr::web::test {
namespace {
namespace json = boost::json;
namespace bhttp = boost::beast::http;

struct QrFixture : ::testing::Test {
  FakeDaemonApi api;
  WebServerOptions opts = [] {
    WebServerOptions o;
    o.token = "installer-token-0123456789abcdef";
    return o;
  }();
  ApiHandler handler{api, opts};

  Response post(const std::string& target, const std::string& body, const std::string& auth = "") {
    Request req{bhttp::verb::post, target, 11};
    req.set(bhttp::field::content_type, "application/json");
    if (!auth.empty()) req.set(bhttp::field::authorization, "Bearer " + auth);
    req.body() = body;
    req.prepare_payload();
    return handler.handle(req);
  }
  // A paired device's token, paired with a 6-digit code the installer made.
  std::string pairWithCode(const std::string& name) {
    const auto code = json::parse(post("/api/pair/code", "", opts.token).body()).at("code").as_string();
    const auto r = post("/api/pair", R"({"code": ")" + std::string(code) + R"(", "name": ")" + name + "\"}");
    EXPECT_EQ(r.result_int(), 200) << r.body();
    return std::string(json::parse(r.body()).at("token").as_string());
  }
  bool anyEvent(const std::string& text) {
    for (const auto& e : api.securityEvents())
      if (e.find(text) != std::string::npos) return true;
    return false;
  }
};

TEST_F(QrFixture, AnUnpairedClientCannotMakeAQrCode) {
  EXPECT_EQ(post("/api/pair/qr", "").result_int(), 401);
  EXPECT_EQ(post("/api/pair/qr", "", "not-a-paired-token").result_int(), 403);
  Request get{bhttp::verb::get, "/api/pair/qr", 11};
  get.set(bhttp::field::authorization, "Bearer " + opts.token);
  EXPECT_EQ(handler.handle(get).result_int(), 405);
}

TEST_F(QrFixture, APairedPhonesQrCodePairsTheNextPhoneOnceAndNamesWhoMadeIt) {
  const std::string skipper = pairWithCode("Skipper phone");
  const auto made = post("/api/pair/qr", "", skipper);
  ASSERT_EQ(made.result_int(), 200) << made.body();
  const auto j = json::parse(made.body());
  const std::string code(j.at("code").as_string());
  EXPECT_EQ(code.size(), kQrCodeLength);
  EXPECT_EQ(j.at("expires_in_s").as_int64(), 600);
  EXPECT_TRUE(anyEvent("QR code for pairing another device made by device \"Skipper phone\""));
  const auto crew = post("/api/pair", R"({"code": ")" + code + R"(", "name": "Crew phone"})");
  ASSERT_EQ(crew.result_int(), 200) << crew.body();
  EXPECT_TRUE(anyEvent("Paired device \"Crew phone\""));
  EXPECT_TRUE(anyEvent("with a QR code made by device \"Skipper phone\""));
  const auto again = post("/api/pair", R"({"code": ")" + code + R"(", "name": "Third phone"})");
  EXPECT_EQ(again.result_int(), 403) << "single use: " << again.body();
  EXPECT_EQ(json::parse(again.body()).at("tries_left").as_int64(), kMaxWrongTries - 1);
  EXPECT_EQ(handler.pairing().devices().size(), 2u);
}

TEST_F(QrFixture, AQrCodeAndThe6DigitCodeLiveSideBySide) {
  const auto six = json::parse(post("/api/pair/code", "", opts.token).body()).at("code").as_string();
  const auto qr = json::parse(post("/api/pair/qr", "", opts.token).body()).at("code").as_string();
  EXPECT_EQ(post("/api/pair", R"({"code": ")" + std::string(qr) + R"(", "name": "a"})").result_int(), 200);
  EXPECT_EQ(post("/api/pair", R"({"code": ")" + std::string(six) + R"(", "name": "b"})").result_int(), 200)
      << "making a QR code does not void the typed code";
}

TEST(QrCode, ItExpiresAfterTenMinutesOfElapsedTime) {
  std::int64_t ms = 5'000'000;
  for (const std::int64_t age : {kCodeLifetimeMs - 1, kCodeLifetimeMs}) {
    Pairing p{std::make_shared<MemoryAuthStore>(), [&] { return ms; }};
    const auto c = p.newQrCode("the installer token");
    ms += age;
    EXPECT_EQ(p.pair(c.code, "late").kind == Pairing::Outcome::Paired, age < kCodeLifetimeMs) << age;
  }
}

TEST(QrCode, AnotherCodeOfTheSameLengthIsAWrongCode) {
  Pairing p{std::make_shared<MemoryAuthStore>()};
  const auto c = p.newQrCode("x");
  std::string wrong = c.code;
  wrong[0] = wrong[0] == 'a' ? 'b' : 'a';
  const auto r = p.pair(wrong, "guesser");
  EXPECT_EQ(r.kind, Pairing::Outcome::WrongCode);
  EXPECT_EQ(p.pair(c.code, "owner").kind, Pairing::Outcome::Paired);
}

}  // namespace
}  // namespace xr::web::test
