#include "drivers/onewire/w1_therm.h"

#include <dirent.h>

#include <algorithm>
#include <charconv>

namespace xr::w1 {

const char* toString(ParseError e) noexcept {
  switch (e) {
    case ParseError::None:
      return "ok";
    case ParseError::Empty:
      return "empty read (conversion failed or sensor gone)";
    case ParseError::Malformed:
      return "malformed w1_slave text";
    case ParseError::CrcNo:
      return "CRC mismatch (crc=.. NO)";
    case ParseError::PowerOnValue:
      return "85000 power-on value (no conversion happened)";
  }
  return "?";
}

W1Reading parseW1Slave(std::string_view text) noexcept {
  W1Reading r;
  if (text.empty()) {
    r.error = ParseError::Empty;
    return r;
  }
  const auto nl = text.find('\n');
  if (nl == std::string_view::npos) {
    r.error = ParseError::Malformed;
    return r;
  }
  std::string_view line1 = text.substr(0, nl);
  std::string_view line2 = text.substr(nl + 1);
  while (!line1.empty() && (line1.back() == '\r' || line1.back() == ' ')) line1.remove_suffix(1);
  // Line 1 must end in ": crc=XX YES" (facts §3: accept t= only then).
  const auto crc = line1.find("crc=");
  if (crc == std::string_view::npos || line1.find(':') == std::string_view::npos) {
    r.error = ParseError::Malformed;
    return r;
  }
  if (line1.size() >= 3 && line1.substr(line1.size() - 3) == "YES") {
    // ok
  } else if (line1.size() >= 2 && line1.substr(line1.size() - 2) == "NO") {
    r.error = ParseError::CrcNo;
    return r;
  } else {
    r.error = ParseError::Malformed;
    return r;
  }
  const auto t = line2.find("t=");
  if (t == std::string_view::npos) {
    r.error = ParseError::Malformed;
    return r;
  }
  std::string_view num = line2.substr(t + 2);
  while (!num.empty() && (num.back() == '\n' || num.back() == '\r' || num.back() == ' '))
    num.remove_suffix(1);
  int v = 0;
  const auto [p, ec] = std::from_chars(num.data(), num.data() + num.size(), v);
  if (ec != std::errc() || p != num.data() + num.size() || num.empty()) {
    r.error = ParseError::Malformed;
    return r;
  }
  if (v == 85000) {
    r.error = ParseError::PowerOnValue;
    return r;
  }
  // DS18B20 range is -55..+125 °C; anything else is not a real reading.
  if (v < -55000 || v > 125000) {
    r.error = ParseError::Malformed;
    return r;
  }
  r.milliC = v;
  return r;
}

std::vector<std::string> listDs18b20(const std::string& root) {
  std::vector<std::string> out;
  DIR* d = ::opendir(root.c_str());
  if (!d) return out;
  while (dirent* e = ::readdir(d)) {
    const std::string_view n(e->d_name);
    if (n.size() > 3 && n.substr(0, 3) == "28-") out.emplace_back(n);
  }
  ::closedir(d);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace xr::w1
