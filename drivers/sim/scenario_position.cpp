// The scenario file's [gps] (a simulated GNSS receiver on NMEA 2000) and
// [weather] (the forecast client in --sim). Errors name file:line: like
// every other scenario key.
#include "drivers/sim/scenario_toml.h"

namespace xr::sim::scenario_toml {

void parseGps(const Ctx& c, const toml::table& t, ScenarioGps& g) {
  g.enabled = true;
  bool lat = false, lon = false;
  for (auto&& [k, v] : t) {
    const auto n = k.str();
    if (n == "latitude") {
      g.latitude = number(c, k, v, -90.0, 90.0);
      lat = true;
    } else if (n == "longitude") {
      g.longitude = number(c, k, v, -180.0, 180.0);
      lon = true;
    } else if (n == "pgn") {
      const double p = number(c, k, v, 0.0, 1.0e6);
      if (p != 129025.0 && p != 129029.0) c.fail(lineOf(v), "[gps] pgn must be 129025 or 129029");
      g.pgn = static_cast<std::uint32_t>(p);
    } else {
      unknownKey(c, k, "[gps]");
    }
  }
  if (!lat || !lon) c.fail(lineOf(t), "[gps] needs latitude and longitude");
}

void parseWeather(const Ctx& c, const toml::table& t, ScenarioWeather& w) {
  for (auto&& [k, v] : t) {
    const auto n = k.str();
    if (n == "url") {
      w.url = text(c, k, v);
    } else if (n == "latitude") {
      w.latitude = number(c, k, v, -90.0, 90.0);
    } else if (n == "longitude") {
      w.longitude = number(c, k, v, -180.0, 180.0);
    } else if (n == "refresh_min") {
      const double r = number(c, k, v, 1.0, 1440.0);
      if (r != static_cast<double>(static_cast<int>(r)))
        c.fail(lineOf(v), "[weather] refresh_min must be whole");
      w.refresh_min = static_cast<int>(r);
    } else {
      unknownKey(c, k, "[weather]");
    }
  }
  if (!w.url.starts_with("http://")) c.fail(lineOf(t), "[weather] needs url = \"http://host[:port]/path\"");
}

}  // namespace xr::sim::scenario_toml
