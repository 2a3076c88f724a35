#include "config/web_checks.h"

#include <arpa/inet.h>
#include <sys/stat.h>

#include <cstdint>
#include <cstdio>

namespace xr {

bool isNumericListenAddress(std::string_view text) {
  if (text.empty() || text.size() > 64) return false;
  const std::string s(text);
  unsigned char buf[sizeof(in6_addr)];
  return inet_pton(AF_INET, s.c_str(), buf) == 1 || inet_pton(AF_INET6, s.c_str(), buf) == 1;
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
