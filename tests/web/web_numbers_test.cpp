// The API's numbers as an owner reads them: plain decimals (13.01), never the
// exponent form Boost.JSON writes by default (1.301E1), on every GET route
// and in the WebSocket frames (docs/dashboard.md, "Numbers").
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/json.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "tests/web/fake_daemon_api.h"
#include "tests/web/http_client.h"
#include "web/server/json_text.h"
#include "web/server/web_server.h"

namespace xr::web::test {
namespace {
namespace json = boost::json;

constexpr const char* kToken = "numbers-test-token";

// The first number token written in exponent form, outside strings ("" when
// there is none). Strings are skipped so "1E1" in a help text is no finding.
std::string exponentNumber(const std::string& text) {
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        inString = false;
      continue;
    }
    if (c == '"') {
      inString = true;
      continue;
    }
    const bool startsNumber =
        (c == '-' || std::isdigit(static_cast<unsigned char>(c))) &&
        (i == 0 || std::string_view(",:[ ").find(text[i - 1]) != std::string_view::npos);
    if (!startsNumber) continue;
    std::size_t j = i + 1;
    while (j < text.size() && std::string_view("0123456789.eE+-").find(text[j]) != std::string_view::npos)
      ++j;
    const std::string token = text.substr(i, j - i);
    if (token.find_first_of("eE") != std::string::npos) return token;
    i = j - 1;
  }
  return "";
}

TEST(JsonNumbers, DoublesArePlainDecimals) {
  EXPECT_EQ(jsonText(json::value(13.01)), "13.01");
  EXPECT_EQ(jsonText(json::value(-0.5)), "-0.5");
  EXPECT_EQ(jsonText(json::value(1700000000.25)), "1700000000.25");
  EXPECT_EQ(jsonText(json::value(0.0001)), "0.0001");
  EXPECT_EQ(jsonText(json::value(-0.0)), "0");
  EXPECT_EQ(jsonText(json::value(100.0)), "100");
  EXPECT_EQ(jsonText(json::value(std::numeric_limits<double>::quiet_NaN())), "null");
  EXPECT_EQ(jsonText(json::value(std::numeric_limits<double>::infinity())), "null");
}

TEST(JsonNumbers, StructureAndStringsAreUnchanged) {
  json::object o;
  o["a\"b"] = json::array{1, 2.5, nullptr, true, "x\ny"};
  o["n"] = std::int64_t{-7};
  const std::string text = jsonText(o);
  EXPECT_EQ(text, R"({"a\"b":[1,2.5,null,true,"x\ny"],"n":-7})");
  EXPECT_EQ(json::parse(text), json::value(o));
}

TEST(JsonNumbers, ExponentFinderSeesExponentsAndIgnoresStrings) {
  EXPECT_EQ(exponentNumber(R"({"v":1.301E1})"), "1.301E1");
  EXPECT_EQ(exponentNumber(R"([2,-4e-3])"), "-4e-3");
  EXPECT_EQ(exponentNumber(R"({"help":"1E1 A","v":13.01})"), "");
}

class JsonNumbersRoutes : public ::testing::Test {
 protected:
  void SetUp() override {
    WebServerOptions o;
    o.listen = "127.0.0.1";
    o.port = 0;
    o.token = kToken;
    o.telemetry_rate_hz = 20;
    server_ = std::make_unique<WebServer>(api_, o);
    server_->start();
  }
  FakeDaemonApi api_;
  std::unique_ptr<WebServer> server_;
};

TEST_F(JsonNumbersRoutes, EveryGetRouteAndTheWebSocketFrameHaveNoExponent) {
  const std::map<std::string, std::string> auth{{"Authorization", std::string("Bearer ") + kToken}};
  const auto port = server_->port();
  for (int i = 0; i < 5; ++i) api_.publish();
  for (const std::string target :
       {"/api/status", "/api/events", "/api/system", "/api/params", "/api/commands", "/api/pair/devices",
        "/api/history?series=battery_v,bcur_a,temp_f,soc_pct&from=-600&step=1", "/api/history/days",
        "/api/history/charges", "/api/no-such-route"}) {
    const auto r = httpRequest(port, bhttp::verb::get, target, "", auth);
    ASSERT_FALSE(r.body.empty()) << target;
    EXPECT_NO_THROW(json::parse(r.body)) << target;
    EXPECT_EQ(exponentNumber(r.body), "") << target << ": " << r.body.substr(0, 300);
  }
  // A status with decimals in it, so the check above could have failed.
  const auto status = httpRequest(port, bhttp::verb::get, "/api/status", "", auth);
  EXPECT_NE(status.body.find("\"wall_time_s\":17"), std::string::npos) << status.body.substr(0, 300);
  WsClient ws(port, std::string("/ws?token=") + kToken);
  for (int i = 0; i < 3; ++i) {
    api_.publish();
    const std::string frame = ws.read();
    EXPECT_NE(frame.find("\"battery_v\":"), std::string::npos);
    EXPECT_EQ(exponentNumber(frame), "") << frame.substr(0, 300);
  }
}

// The most decimals any number outside strings carries.
std::size_t longestFraction(const std::string& text) {
  std::size_t most = 0;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        inString = false;
      continue;
    }
    if (c == '"') {
      inString = true;
      continue;
    }
    if (c != '.' || i == 0 || !std::isdigit(static_cast<unsigned char>(text[i - 1]))) continue;
    std::size_t j = i + 1;
    while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) ++j;
    most = std::max(most, j - i - 1);
  }
  return most;
}

// The reproducers: "age_s": 1.8984e-05 in /api/system and 17-digit floats
// in the history routes. Each is now rounded to what it resolves (the
// status rounding, json_status.h): at most 4 decimals anywhere.
TEST_F(JsonNumbersRoutes, SystemAndHistoryNumbersAreRoundedToTheirResolution) {
  const std::map<std::string, std::string> auth{{"Authorization", std::string("Bearer ") + kToken}};
  const auto port = server_->port();
  api_.publish();
  for (const std::string target :
       {"/api/system", "/api/history?series=battery_v,bcur_a,temp_f,soc_pct&from=-600&step=1",
        "/api/history/days", "/api/history/charges"}) {
    const auto r = httpRequest(port, bhttp::verb::get, target, "", auth);
    ASSERT_EQ(r.status, 200) << target;
    EXPECT_LE(longestFraction(r.body), 4u) << target << ": " << r.body.substr(0, 400);
  }
  const auto days = json::parse(httpRequest(port, bhttp::verb::get, "/api/history/days", "", auth).body);
  const auto& day = days.at("days").at(0);
  EXPECT_EQ(day.at("alt_ah"), json::value(123.4568));
  EXPECT_EQ(day.at("min_soc_pct"), json::value(std::int64_t{0}));
  const auto h = json::parse(
      httpRequest(port, bhttp::verb::get, "/api/history?series=battery_v&from=-600&step=1", "", auth).body);
  const double v = h.at("series").at("battery_v").at(0).to_number<double>();
  EXPECT_EQ(v, std::round(v * 1000.0) / 1000.0);  // volts: 3 decimals
}

}  // namespace
}  // namespace xr::web::test
