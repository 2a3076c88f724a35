// Unit tests of the web server's pure helpers: token compare, Bearer parsing,
// listen-address parsing, token generation, static path resolution, query parsing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "web/server/api_handler.h"
#include "web/server/auth.h"
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

// Issue 26, item 12: dotfiles in www_root are never served; a file that only
// contains a dot elsewhere is.
TEST(WebStatic, DotfilesAreNotServed) {
  char tmpl[] = "/tmp/xr-www-XXXXXX";
  const std::string root = mkdtemp(tmpl);
  std::filesystem::create_directory(root + "/.git");
  for (const char* f : {"/.env", "/.git/config", "/app.min.js", "/index.html"}) std::ofstream(root + f) << "x";
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

}  // namespace
}  // namespace xr::web
