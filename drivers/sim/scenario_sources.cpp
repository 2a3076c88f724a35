// Other charge sources and the fridge in a scenario file: [solar],
// [charger] and the fridge keys of [loads] (docs/simulator.md "Other charge
// sources", "Loads").
#include <string>

#include "drivers/sim/scenario_toml.h"

namespace xr::sim::scenario_toml {

void parseChargeSource(const Ctx& c, const toml::table& t, ChargeSourceConfig& s, bool solar) {
  const std::string where = solar ? "[solar]" : "[charger]";
  s.present = true;
  s.solar = solar;
  struct F {
    std::string_view name;
    double ChargeSourceConfig::*field;
    double lo, hi;
    bool solarOnly;
  };
  static const F fields[] = {
      {"max_a", &ChargeSourceConfig::max_a, 0.1, 1000.0, false},
      {"absorption_v", &ChargeSourceConfig::absorption_v, 1.0, 80.0, false},
      {"float_v", &ChargeSourceConfig::float_v, 1.0, 80.0, false},
      {"rebulk_v", &ChargeSourceConfig::rebulk_v, 1.0, 80.0, false},
      {"absorption_s", &ChargeSourceConfig::absorption_s, 0.0, 1.0e6, false},
      {"tail_a", &ChargeSourceConfig::tail_a, 0.0, 1000.0, false},
      {"start_h", &ChargeSourceConfig::start_h, 0.0, 24.0, true},
      {"sunrise_h", &ChargeSourceConfig::sunrise_h, 0.0, 24.0, true},
      {"sunset_h", &ChargeSourceConfig::sunset_h, 0.0, 24.0, true},
  };
  for (auto&& [k, v] : t) {
    if (!solar && k.str() == "on") {
      if (!v.is_boolean()) c.fail(lineOf(v), "[charger] on must be true or false");
      s.on = *v.value<bool>();
      continue;
    }
    bool found = false;
    for (const auto& f : fields) {
      if (k.str() == f.name && (solar || !f.solarOnly)) {
        s.*(f.field) = number(c, k, v, f.lo, f.hi);
        found = true;
      }
    }
    if (!found) unknownKey(c, k, where);
  }
  if (solar && !(s.sunset_h > s.sunrise_h)) c.fail(lineOf(t), "[solar] sunset_h must come after sunrise_h");
  if (s.float_v > 0.0 && s.absorption_v > 0.0 && s.float_v > s.absorption_v)
    c.fail(lineOf(t), where + " float_v is above absorption_v");
}

bool parseLoadKey(const Ctx& c, const toml::key& k, const toml::node& v, PlantConfig& p) {
  const auto n = k.str();
  if (n == "house_a")
    p.house_a = number(c, k, v, 0.0, 2000.0);
  else if (n == "fridge_a")
    p.fridge_a = number(c, k, v, 0.0, 100.0);
  else if (n == "fridge_duty")
    p.fridge_duty = number(c, k, v, 0.0, 1.0);
  else if (n == "fridge_period_s")
    p.fridge_period_s = number(c, k, v, 10.0, 86400.0);
  else
    return false;
  return true;
}

}  // namespace xr::sim::scenario_toml
