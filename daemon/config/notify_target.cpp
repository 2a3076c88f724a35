#include "config/notify_target.h"

#include <cctype>
#include <string_view>

namespace xr {

namespace {
bool fail(std::string* why, const char* text) {
  if (why) *why = text;
  return false;
}
// RFC 9110 token characters: a header name.
bool isToken(std::string_view s) {
  if (s.empty()) return false;
  for (unsigned char c : s)
    if (!std::isalnum(c) &&
        std::string_view("!#$%&'*+-.^_`|~").find(static_cast<char>(c)) == std::string_view::npos)
      return false;
  return true;
}
bool printable(std::string_view s) {
  for (unsigned char c : s)
    if (c < 0x20 || c == 0x7f) return false;
  return true;
}
}  // namespace

std::optional<NotifyUrl> parseNotifyUrl(const std::string& url, std::string* why) {
  NotifyUrl u;
  std::string_view rest(url);
  if (rest.starts_with("https://")) {
    u.tls = true;
    rest.remove_prefix(8);
  } else if (rest.starts_with("http://")) {
    rest.remove_prefix(7);
  } else {
    fail(why, "must start with http:// or https://");
    return std::nullopt;
  }
  const auto end = rest.find_first_of("/?");
  const std::string_view hostPort = rest.substr(0, end);
  std::string target(end == std::string_view::npos ? std::string_view("/") : rest.substr(end));
  if (target.front() == '?') target.insert(0, "/");
  if (!printable(url) || url.find(' ') != std::string::npos || hostPort.find('@') != std::string_view::npos) {
    fail(why, "must not hold spaces, control characters or user:password@ (put a token in header)");
    return std::nullopt;
  }
  const auto colon = hostPort.rfind(':');
  u.host = std::string(hostPort.substr(0, colon));
  u.port = colon == std::string_view::npos ? (u.tls ? "443" : "80") : std::string(hostPort.substr(colon + 1));
  u.target = std::move(target);
  if (u.host.empty() || u.host.find(':') != std::string::npos) {
    fail(why, "names no host");
    return std::nullopt;
  }
  const bool digits =
      !u.port.empty() && u.port.size() <= 5 && u.port.find_first_not_of("0123456789") == std::string::npos;
  if (!digits || std::stoi(u.port) < 1 || std::stoi(u.port) > 65535) {
    fail(why, "has a port that is not 1 to 65535");
    return std::nullopt;
  }
  return u;
}

std::optional<NotifyHeader> parseNotifyHeader(const std::string& text, std::string* why) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) {
    fail(why, "must be \"Name: value\"");
    return std::nullopt;
  }
  NotifyHeader h{text.substr(0, colon), text.substr(colon + 1)};
  while (!h.value.empty() && h.value.front() == ' ') h.value.erase(0, 1);
  while (!h.value.empty() && h.value.back() == ' ') h.value.pop_back();
  if (!isToken(h.name)) {
    fail(why, "has no usable header name before the ':' (letters, digits and -)");
    return std::nullopt;
  }
  if (h.value.empty() || !printable(h.value)) {
    fail(why, "has an empty value or a line break in it");
    return std::nullopt;
  }
  return h;
}

}  // namespace xr
