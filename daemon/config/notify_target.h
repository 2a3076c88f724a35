#pragma once
// Where [notify] sends (docs/integrations.md "Alarms that reach the owner"):
// the URL and the extra header, parsed once for the loader's check and the
// sender, so the two never disagree about what is usable.
#include <optional>
#include <string>

namespace xr {

struct NotifyUrl {
  bool tls = false;                // https://
  std::string host, port, target;  // target: path and query, "/" at least
};
// http(s)://host[:port][/path[?query]]; nullopt with `why` set otherwise.
std::optional<NotifyUrl> parseNotifyUrl(const std::string& url, std::string* why = nullptr);

struct NotifyHeader {
  std::string name, value;
};
// "Name: value" with a token name and a value without line breaks; nullopt
// with `why` set otherwise.
std::optional<NotifyHeader> parseNotifyHeader(const std::string& text, std::string* why = nullptr);

}  // namespace xr
