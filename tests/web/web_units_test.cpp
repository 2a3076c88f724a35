// Unit tests of the web server's pure helpers: token compare, Bearer parsing,
// listen-address parsing, token generation, static path resolution, query parsing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "web/server/api_handler.h"
#include "web/server/auth.h"
#include "web/server/json_status.h"
#include "web/server/static_files.h"
#include "web/server/web_server.h"

namespace xr::web {
namespace {

TEST(WebAuth, ConstantTimeEqualsOnlyForIdenticalNonEmpty) {
  EXPECT_TRUE(constantTimeEquals("abc", "abc"));
  EXPECT_FALSE(constantTimeEquals("abd", "abc"));
  EXPECT_FALSE(constantTimeEquals("ab", "abc"));
  EXPECT_FALSE(constantTimeEquals("abcd", "abc"));
  EXPECT_FALSE(constantTimeEquals("", ""));  // an empty token never matches
}

TEST(WebAuth, BearerMissingVsForbidden) {
  EXPECT_EQ(checkBearer("", "", "t0k"), AuthResult::Missing);
  EXPECT_EQ(checkBearer("Bearer t0k", "", "t0k"), AuthResult::Ok);
  EXPECT_EQ(checkBearer("bearer   t0k ", "", "t0k"), AuthResult::Ok);
  EXPECT_EQ(checkBearer("Bearer t0", "", "t0k"), AuthResult::Forbidden);
  EXPECT_EQ(checkBearer("Basic t0k", "", "t0k"), AuthResult::Forbidden);
  EXPECT_EQ(checkBearer("", "t0k", "t0k"), AuthResult::Ok);
  EXPECT_EQ(checkBearer("", "bad", "t0k"), AuthResult::Forbidden);
}

TEST(WebOptions, ParseListenAddress) {
  WebServerOptions o;
  EXPECT_TRUE(parseListenAddress("127.0.0.1:9000", o));
  EXPECT_EQ(o.listen, "127.0.0.1");
  EXPECT_EQ(o.port, 9000);
  EXPECT_TRUE(parseListenAddress("[::1]:81", o));
  EXPECT_EQ(o.listen, "::1");
  EXPECT_EQ(o.port, 81);
  EXPECT_TRUE(parseListenAddress(":8080", o));
  EXPECT_EQ(o.listen, "0.0.0.0");
  for (const char* bad : {"127.0.0.1", "127.0.0.1:", "127.0.0.1:70000", "1.2.3.4:80x", "[::1:80"}) {
    WebServerOptions before = o;
    EXPECT_FALSE(parseListenAddress(bad, o)) << bad;
    EXPECT_EQ(o.port, before.port);
  }
}

TEST(WebOptions, FromSettingsCopiesWebTable) {
  WebSettings s;
  s.listen = "0.0.0.0";
  s.port = 8081;
  s.telemetry_rate_hz = 20;
  s.reads_require_token = true;
  s.max_connections = 7;
  s.www_root = "/usr/share/xregulator/www";
  const auto o = WebServerOptions::fromSettings(s, "tok");
  EXPECT_EQ(o.listen, "0.0.0.0");
  EXPECT_EQ(o.port, 8081);
  EXPECT_EQ(o.token, "tok");
  EXPECT_TRUE(o.reads_require_token);
  EXPECT_EQ(o.max_connections, 7);
  EXPECT_EQ(o.www_root, s.www_root);
}

TEST(WebToken, GeneratedTokensAre64HexAndDistinct) {
  std::set<std::string> seen;
  for (int i = 0; i < 8; ++i) {
    const auto t = generateToken();
    EXPECT_EQ(t.size(), 64u);
    EXPECT_EQ(t.find_first_not_of("0123456789abcdef"), std::string::npos);
    seen.insert(t);
  }
  EXPECT_EQ(seen.size(), 8u);
}

TEST(WebStatic, MimeTypes) {
  EXPECT_EQ(mimeType("a/index.html"), "text/html; charset=utf-8");
  EXPECT_EQ(mimeType("x.min.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(mimeType("u.css"), "text/css; charset=utf-8");
  EXPECT_EQ(mimeType("i.svg"), "image/svg+xml");
  EXPECT_EQ(mimeType("noext"), "application/octet-stream");
}

TEST(WebStatic, RejectsTraversalWithoutTouchingDisk) {
  for (const char* bad : {"", "x", "/..", "/../etc/passwd", "/a/../b", "/%2e%2e/x", "/a\\b", "//x"})
    EXPECT_FALSE(resolveStaticPath("/usr/share", bad).has_value()) << bad;
  EXPECT_FALSE(resolveStaticPath("", "/index.html").has_value());
}

// dotfiles in www_root are never served; a file that only
// contains a dot elsewhere is.
TEST(WebStatic, DotfilesAreNotServed) {
  char tmpl[] = "/tmp/xr-www-XXXXXX";
  const std::string root = mkdtemp(tmpl);
  std::filesystem::create_directory(root + "/.git");
  for (const char* f : {"/.env", "/.git/config", "/app.min.js", "/index.html"})
    std::ofstream(root + f) << "x";
  for (const char* bad : {"/.env", "/.git/config", "/.git/", "/./index.html"})
    EXPECT_FALSE(resolveStaticPath(root, bad).has_value()) << bad;
  EXPECT_TRUE(resolveStaticPath(root, "/app.min.js").has_value());
  EXPECT_TRUE(resolveStaticPath(root, "/").has_value());
  std::filesystem::remove_all(root);
}

TEST(WebOptions, KeepAliveIdleTimeoutIsTheDocumentedTenSeconds) {
  EXPECT_EQ(WebServerOptions{}.keepalive_timeout, std::chrono::seconds(10));
}

TEST(WebQuery, PercentDecodeAndParams) {
  bool ok = false;
  EXPECT_EQ(percentDecode("a%20b+c", &ok), "a b c");
  EXPECT_TRUE(ok);
  percentDecode("%zz", &ok);
  EXPECT_FALSE(ok);
  percentDecode("%2", &ok);
  EXPECT_FALSE(ok);
  EXPECT_EQ(queryParam("a=1&series=battery_v%2Calt_a&b", "series").value(), "battery_v,alt_a");
  EXPECT_EQ(queryParam("a=1&b", "b").value(), "");
  EXPECT_FALSE(queryParam("a=1", "b").has_value());
}

// one naming style, rounded numbers, integers, null sentinels.
TEST(WebStatusShape, SnakeCaseNames) {
  EXPECT_EQ(snakeName("lockoutRemainingS"), "lockout_remaining_s");
  EXPECT_EQ(snakeName("SOC_percent"), "soc_percent");
  EXPECT_EQ(snakeName("g_awState"), "aw_state");
  EXPECT_EQ(snakeName("cvDSlope"), "cv_d_slope");
  EXPECT_EQ(snakeName("ChargedEnergy_AllTime_Wh"), "charged_energy_all_time_wh");
  EXPECT_EQ(snakeName("IBV_filtered"), "ibv_filtered");
  EXPECT_EQ(snakeName("I_cap"), "i_cap");
  EXPECT_EQ(snakeName("batteryCurrentForSoC"), "battery_current_for_soc");
  EXPECT_EQ(snakeName("sysIDRunning"), "sys_id_running");
  EXPECT_EQ(snakeName("battery_v"), "battery_v");  // CSV names are unchanged
}

TEST(WebStatusShape, RoundedToSensorResolution) {
  EXPECT_DOUBLE_EQ(statusNumber("battery_v", 12.580859375000001).as_double(), 12.581);
  EXPECT_DOUBLE_EQ(statusNumber("alt_a", 16.88125).as_double(), 16.88);
  EXPECT_DOUBLE_EQ(statusNumber("temp_f", 80.2366).as_double(), 80.2);
  EXPECT_EQ(statusNumber("temp_f", 80.0366).as_int64(), 80);  // whole after rounding: an integer
  EXPECT_EQ(statusNumber("rpm", 1800.5625).as_int64(), 1801);
  EXPECT_EQ(statusNumber("soc_pct", 99.995).as_int64(), 100);
  EXPECT_DOUBLE_EQ(statusNumber("soc_pct", 99.94).as_double(), 99.9);
  EXPECT_DOUBLE_EQ(statusNumber("wall_time_s", 1796306371.8951).as_double(), 1796306371.895);
}

TEST(WebStatusShape, CountersAreIntegersAndSentinelsNull) {
  EXPECT_TRUE(statusNumber("watchdog_feeds", 2327.0).is_int64());
  EXPECT_EQ(statusNumber("watchdog_feeds", 2327.0).as_int64(), 2327);
  EXPECT_TRUE(statusNumber("time_to_full_discharge_min", -999.0).is_null());
  EXPECT_TRUE(statusNumber("battery_v", std::nan("")).is_null());
  EXPECT_FALSE(statusNumber("dvdt", -998.5).is_null());    // just above the sentinel is a value
  EXPECT_TRUE(statusNumber("dvdt", -0.00001).is_int64());  // rounds to 0, never "-0"
  EXPECT_EQ(statusNumber("dvdt", -0.00001).as_int64(), 0);
}

}  // namespace
}  // namespace xr::web
