// WebServerOptions from [web] settings, --http ADDR:PORT parsing, token generation.
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "web/server/web_server.h"

// Set by web/CMakeLists.txt; empty in builds that never serve files (fuzzer).
#ifndef XR_WWW_BUILD_DIR
#define XR_WWW_BUILD_DIR ""
#endif
#ifndef XR_WWW_INSTALL_DIR
#define XR_WWW_INSTALL_DIR ""
#endif

namespace xr::web {

WebServerOptions WebServerOptions::fromSettings(const WebSettings& s, std::string token) {
  WebServerOptions o;
  o.listen = s.listen;
  o.port = static_cast<std::uint16_t>(s.port);
  o.token = std::move(token);
  o.telemetry_rate_hz = s.telemetry_rate_hz;
  o.reads_require_token = s.reads_require_token;
  o.max_connections = s.max_connections;
  o.www_root = s.www_root;
  return o;
}

bool parseListenAddress(const std::string& text, WebServerOptions& opts) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos) return false;
  std::string host = text.substr(0, colon);
  const std::string portText = text.substr(colon + 1);
  unsigned port = 0;
  const auto* end = portText.data() + portText.size();
  auto [p, ec] = std::from_chars(portText.data(), end, port);
  if (portText.empty() || ec != std::errc{} || p != end || port > 65535) return false;
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  if (host.find_first_of("[]") != std::string::npos) return false;
  if (host.empty()) host = "0.0.0.0";
  opts.listen = host;
  opts.port = static_cast<std::uint16_t>(port);
  return true;
}

std::string generateToken() {
  std::ifstream in("/dev/urandom", std::ios::binary);
  unsigned char bytes[32];
  if (!in.read(reinterpret_cast<char*>(bytes), sizeof bytes))
    throw std::runtime_error("cannot read /dev/urandom for the web token");
  std::string hex;
  hex.reserve(64);
  static constexpr char kDigits[] = "0123456789abcdef";
  for (unsigned char b : bytes) {
    hex.push_back(kDigits[b >> 4]);
    hex.push_back(kDigits[b & 0xf]);
  }
  return hex;
}

std::string defaultWwwRoot() {
  std::error_code ec;
  if (std::filesystem::is_regular_file(std::filesystem::path(XR_WWW_INSTALL_DIR) / "index.html", ec))
    return XR_WWW_INSTALL_DIR;
  return XR_WWW_BUILD_DIR;
}

}  // namespace xr::web
