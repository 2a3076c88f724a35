// Naming and rounding of the /api/status values (see json_status.h).
#include "web/server/json_status.h"

#include <cctype>
#include <cmath>
#include <cstdint>

namespace xr::web {
namespace json = boost::json;

namespace {
bool upper(char c) { return std::isupper(static_cast<unsigned char>(c)) != 0; }
bool lowerOrDigit(char c) {
  return std::islower(static_cast<unsigned char>(c)) != 0 || std::isdigit(static_cast<unsigned char>(c)) != 0;
}
bool endsWith(std::string_view s, std::string_view end) {
  return s.size() >= end.size() && s.substr(s.size() - end.size()) == end;
}
bool has(std::string_view s, std::string_view part) { return s.find(part) != std::string_view::npos; }
}  // namespace

std::string snakeName(std::string_view raw) {
  if (raw.substr(0, 2) == "g_") raw.remove_prefix(2);  // the firmware's globals prefix
  // "SoC" is one word ("batteryCurrentForSoC" -> "battery_current_for_soc").
  std::string name(raw);
  for (auto at = name.find("SoC"); at != std::string::npos; at = name.find("SoC", at)) name[at + 2] = 'c';
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (upper(c) && i > 0 && out.back() != '_') {
      // A word starts at an upper-case letter after a lower-case one or a
      // digit, or at the last capital of an acronym ("SOCPercent").
      const bool afterLower = lowerOrDigit(name[i - 1]);
      const bool acronymEnd = upper(name[i - 1]) && i + 1 < name.size() &&
                              std::islower(static_cast<unsigned char>(name[i + 1])) != 0;
      if (afterLower || acronymEnd) out += '_';
    }
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

int statusDecimals(std::string_view n) {
  if (n == "wall_time_s" || n == "t_s") return 3;
  if (has(n, "rpm")) return 0;
  if (endsWith(n, "_v") || has(n, "voltage") || has(n, "_v_") || n == "vpred" || n == "ibv_filtered")
    return 3;
  if (endsWith(n, "_a") || has(n, "amps") || has(n, "_a_") || n == "i_cap" || n == "i_cmd" || n == "icv" ||
      has(n, "current"))
    return 2;
  if (endsWith(n, "_f") || has(n, "temp") || endsWith(n, "_c")) return 1;
  if (endsWith(n, "_pct") || has(n, "percent") || has(n, "soc") || has(n, "duty")) return 1;
  if (endsWith(n, "_wh") || endsWith(n, "_us") || endsWith(n, "_hz") || endsWith(n, "_min")) return 1;
  if (endsWith(n, "_s") || endsWith(n, "_l")) return 2;
  return 4;
}

json::value statusNumber(std::string_view name, double v) {
  if (!std::isfinite(v) || v <= -999.0) return nullptr;
  const double scale = std::pow(10.0, statusDecimals(name));
  double r = std::round(v * scale) / scale;
  if (r == 0.0) r = 0.0;  // no "-0"
  if (std::fabs(r) < 9.0e15 && r == std::floor(r)) return static_cast<std::int64_t>(r);
  return r;
}

boost::json::object ownerToJson(const owner::OwnerModel& m) {
  namespace json = boost::json;
  json::object o;
  o["state"] = m.state;
  if (!m.notice.empty()) o["notice"] = m.notice;
  json::object hero;
  hero["value"] = statusNumber(m.hero.unit == "V"   ? "battery_v"
                               : m.hero.unit == "A" ? "bcur_a"
                                                    : "soc_pct",
                               m.hero.value);
  hero["unit"] = m.hero.unit;
  hero["label"] = m.hero.label;
  o["hero"] = std::move(hero);
  json::object soc;
  soc["pct"] = statusNumber("soc_pct", m.soc.pct);
  soc["source"] = m.soc.source;
  o["soc"] = std::move(soc);
  json::object bms;
  bms["state"] = m.bms.state;
  bms["words"] = m.bms.words;
  o["bms"] = std::move(bms);
  json::array limits;
  for (const auto& l : m.limits) {
    json::object x;
    x["id"] = l.id;
    x["what"] = l.what;
    x["amps"] = statusNumber("amps_a", l.amps);
    x["why"] = l.why;
    limits.push_back(std::move(x));
  }
  o["limits"] = std::move(limits);
  return o;
}

}  // namespace xr::web
