// candump log lines: format and parse (see candump_log.h).
#include "drivers/can/candump_log.h"

#include <charconv>
#include <cstdio>

namespace xr::can {
namespace {
constexpr std::uint32_t kErrFlag = 0x20000000u;  // CAN_ERR_FLAG (linux/can.h)

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}
}  // namespace

std::string formatCandump(double timeSec, std::string_view interface, const CanFrame& f) {
  char head[64];
  std::snprintf(head, sizeof head, "(%.6f) ", timeSec);
  std::string s = head;
  s += interface;
  char id[16];
  if (f.error)
    std::snprintf(id, sizeof id, " %08X#", static_cast<unsigned>(kErrFlag | (f.id & 0x1FFFFFFFu)));
  else if (f.extended)
    std::snprintf(id, sizeof id, " %08X#", static_cast<unsigned>(f.id & 0x1FFFFFFFu));
  else
    std::snprintf(id, sizeof id, " %03X#", static_cast<unsigned>(f.id & 0x7FFu));
  s += id;
  static constexpr char kHex[] = "0123456789ABCDEF";
  for (int i = 0; i < f.dlc && i < 8; ++i) {
    s += kHex[f.data[i] >> 4];
    s += kHex[f.data[i] & 0xF];
  }
  return s;
}

std::optional<CandumpLine> parseCandump(std::string_view line) {
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r' || line.back() == ' '))
    line.remove_suffix(1);
  if (line.size() < 4 || line.front() != '(') return std::nullopt;
  const auto close = line.find(')');
  if (close == std::string_view::npos) return std::nullopt;
  CandumpLine out;
  const std::string stamp(line.substr(1, close - 1));
  char* end = nullptr;
  out.timeSec = std::strtod(stamp.c_str(), &end);
  if (end == stamp.c_str() || *end != '\0') return std::nullopt;
  std::string_view rest = line.substr(close + 1);
  if (rest.empty() || rest.front() != ' ') return std::nullopt;
  rest.remove_prefix(1);
  const auto sp = rest.find(' ');
  if (sp == std::string_view::npos || sp == 0) return std::nullopt;
  out.interface = std::string(rest.substr(0, sp));
  rest.remove_prefix(sp + 1);
  const auto hash = rest.find('#');
  if (hash == std::string_view::npos || (hash != 3 && hash != 8)) return std::nullopt;
  std::uint32_t id = 0;
  const auto idText = rest.substr(0, hash);
  if (std::from_chars(idText.data(), idText.data() + idText.size(), id, 16).ptr !=
      idText.data() + idText.size())
    return std::nullopt;
  CanFrame& f = out.frame;
  f.extended = hash == 8;
  f.error = f.extended && (id & kErrFlag) != 0;
  f.id = f.extended ? (id & 0x1FFFFFFFu) : id;
  if (!f.extended && id > 0x7FF) return std::nullopt;
  const auto data = rest.substr(hash + 1);
  if (data.size() % 2 != 0 || data.size() > 16) return std::nullopt;
  f.dlc = static_cast<std::uint8_t>(data.size() / 2);
  for (std::size_t i = 0; i < f.dlc; ++i) {
    const int hi = hexDigit(data[2 * i]), lo = hexDigit(data[2 * i + 1]);
    if (hi < 0 || lo < 0) return std::nullopt;
    f.data[i] = static_cast<std::uint8_t>(hi << 4 | lo);
  }
  return out;
}

}  // namespace xr::can
