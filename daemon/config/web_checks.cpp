#include "config/web_checks.h"

#include <arpa/inet.h>
#include <sys/stat.h>

#include <charconv>
#include <cstdint>
#include <cstdio>

namespace xr {

bool isNumericListenAddress(std::string_view text) {
  if (text.empty() || text.size() > 64) return false;
  const std::string s(text);
  unsigned char buf[sizeof(in6_addr)];
  return inet_pton(AF_INET, s.c_str(), buf) == 1 || inet_pton(AF_INET6, s.c_str(), buf) == 1;
}

std::string checkHttpListenText(std::string_view text) {
  const auto colon = text.rfind(':');
  if (colon == std::string_view::npos) return "expected ADDR:PORT, got '" + std::string(text) + "'";
  std::string_view host = text.substr(0, colon);
  const std::string_view port = text.substr(colon + 1);
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (port.empty() || ec != std::errc{} || end != port.data() + port.size() || value > 65535)
    return "'" + std::string(port) + "' is not a port (0..65535) in '" + std::string(text) + "'";
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  if (host.empty()) return {};  // every interface, as "0.0.0.0" (the daemon logs it)
  if (!isNumericListenAddress(host))
    return "'" + std::string(host) +
           "' is not an IP address: write an IPv4 or IPv6 address such as 127.0.0.1:8104 (this machine "
           "only), 0.0.0.0:8104 (every interface) or [::1]:8104";
  return {};
}

bool isEveryInterface(std::string_view listen) {
  return listen.empty() || listen == "0.0.0.0" || listen == "::";
}

std::string checkTokenText(std::string_view token) {
  if (token.empty()) return {};
  for (char c : token)
    if (c < '!' || c > '~')
      return "may contain only printable ASCII characters without spaces (it is sent in an HTTP header)";
  if (token.size() < kMinTokenLength)
    return "is " + std::to_string(token.size()) + " characters; a token needs at least " +
           std::to_string(kMinTokenLength) + " (or leave it empty to use the generated 64-character token)";
  return {};
}

std::string tokenFingerprint(std::string_view token) {
  // FNV-1a 64, folded to 32 bits: a label, not a secret (and not a MAC).
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : token) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char out[9];
  std::snprintf(out, sizeof out, "%08x", static_cast<unsigned>((h >> 32) ^ (h & 0xffffffffULL)));
  return out;
}

std::string tokenFileWarning(const std::string& configPath, std::string_view token) {
  struct stat st {};
  if (token.empty() || ::stat(configPath.c_str(), &st) != 0 || (st.st_mode & S_IROTH) == 0) return {};
  return configPath +
         ": [web] token is set in a file every user of this machine can read; make it readable by "
         "root and the xregulator group only (chown root:xregulator, chmod 640) or leave the token "
         "empty to use the generated one";
}

}  // namespace xr
