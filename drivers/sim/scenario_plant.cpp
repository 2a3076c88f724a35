// The plant sections of a scenario file: [battery], [alternator], [noise]
// (docs/simulator.md). Ranges and cross-checks here are what make a bad plant
// parameter a file:line: error instead of a plant that cannot exist.
#include <cmath>
#include <sstream>

#include "drivers/sim/scenario_toml.h"

namespace xr::sim::scenario_toml {

void parseBattery(const Ctx& c, const toml::table& t, BatteryConfig& b) {
  std::vector<double> socs, volts;
  int ocvLine = lineOf(t), socLine = lineOf(t), voltLine = lineOf(t);
  for (auto&& [k, v] : t) {
    const auto n = k.str();
    if (n == "chemistry") {
      const auto s = text(c, k, v);
      const auto ch = parseChemistry(s);
      if (!ch) c.fail(lineOf(v), "unknown chemistry '" + s + "' (lifepo4 | agm | flooded | gel)");
      b.chemistry = *ch;
    } else if (n == "capacity_ah") {
      b.capacity_ah = number(c, k, v, 1.0, 100000.0);
    } else if (n == "soc_pct") {
      b.soc_pct = number(c, k, v, 0.0, 100.0);
    } else if (n == "nominal_v") {
      b.nominal_v = number(c, k, v, 6.0, 64.0);
    } else if (n == "cells") {
      b.cells = int(number(c, k, v, 1.0, 32.0));
      if (double(b.cells) != *v.value<double>()) c.fail(lineOf(v), "'cells' must be a whole number");
    } else if (n == "r_ohm") {
      b.r_ohm = number(c, k, v, 0.0, 1.0);
    } else if (n == "temp_c") {
      b.temp_c = number(c, k, v, -40.0, 80.0);
    } else if (n == "temp_sensor") {
      if (!v.is_boolean()) c.fail(lineOf(v), "[battery] temp_sensor must be true or false");
      b.temp_sensor = *v.value<bool>();
    } else if (n == "ocv_soc_pct") {
      socs = numbers(c, k, v, 0.0, 100.0);
      ocvLine = socLine = lineOf(v);
    } else if (n == "ocv_cell_v") {
      volts = numbers(c, k, v, 0.0, 10.0);
      ocvLine = voltLine = lineOf(v);
    } else {
      unknownKey(c, k, "[battery]");
    }
  }
  if (socs.empty() != volts.empty()) c.fail(ocvLine, "[battery] ocv_soc_pct and ocv_cell_v go together");
  if (!socs.empty()) {
    if (socs.size() != volts.size()) c.fail(ocvLine, "[battery] ocv_soc_pct and ocv_cell_v differ in length");
    b.ocv.clear();
    for (std::size_t i = 0; i < socs.size(); ++i) b.ocv.push_back({socs[i] / 100.0, volts[i]});
    const auto why = ocvTableProblem(b.ocv);
    const bool aboutVolts = why.find("voltage") != std::string_view::npos;
    if (!why.empty()) c.fail(aboutVolts ? voltLine : socLine, "[battery] OCV table: " + std::string(why));
  }
}

void parseAlternator(const Ctx& c, const toml::table& t, AlternatorConfig& a) {
  struct F {
    std::string_view name;
    double AlternatorConfig::*field;
    double lo, hi;
  };
  // Ranges are what is physical at all (resistances and inductances above
  // zero); whether the machine they make works is checked below.
  static const F fields[] = {
      {"rated_a", &AlternatorConfig::rated_a, 1.0, 1000.0},
      {"cut_in_rpm", &AlternatorConfig::cut_in_rpm, 1.0, 20000.0},
      {"field_tau_s", &AlternatorConfig::field_tau_s, 0.001, 10.0},
      {"pole_pairs", &AlternatorConfig::pole_pairs, 1.0, 24.0},
      {"flux_k", &AlternatorConfig::flux_k, 1e-6, 1.0},
      {"flux_sat_a", &AlternatorConfig::flux_sat_a, 0.01, 1e4},
      {"stator_l_h", &AlternatorConfig::stator_l_h, 1e-7, 0.1},
      {"stator_rx_ohm", &AlternatorConfig::stator_rx_ohm, 0.0, 10.0},
      {"copper_r_ohm", &AlternatorConfig::copper_r_ohm, 1e-5, 10.0},
      {"field_r_ohm", &AlternatorConfig::field_r_ohm, 0.1, 100.0},
      {"field_l_h", &AlternatorConfig::field_l_h, 1e-4, 10.0},
      {"diode_v", &AlternatorConfig::diode_v, 0.0, 3.0},
      {"temp_f", &AlternatorConfig::temp_f, -40.0, 400.0},
      {"ambient_f", &AlternatorConfig::ambient_f, -40.0, 200.0},
      {"pulley_ratio", &AlternatorConfig::pulley_ratio, 0.5, 10.0},
      {"wiring_ohm", &AlternatorConfig::wiring_ohm, 0.0, 1.0},
  };
  for (auto&& [k, v] : t) {
    if (k.str() == "preset") {
      const auto s = text(c, k, v);
      if (!parseAlternatorPreset(s.c_str(), a.preset))
        c.fail(lineOf(v), "unknown alternator preset '" + s +
                              "' (bosch-lix-180 | westerbeke-48 | ford-130 | mercury-52)");
      continue;
    }
    bool found = false;
    for (const auto& f : fields) {
      if (k.str() == f.name) {
        a.*(f.field) = number(c, k, v, f.lo, f.hi);
        found = true;
      }
    }
    if (!found) unknownKey(c, k, "[alternator]");
  }
  try {
    (void)resolveMachine(a);
  } catch (const std::invalid_argument& e) {
    // The line of the first key the message names, else the table's.
    int line = lineOf(t);
    const std::string why = e.what();
    for (auto&& [k, v] : t) {
      if (why.find(std::string(k.str())) != std::string::npos) {
        line = lineOf(v);
        break;
      }
    }
    c.fail(line, std::string("[alternator] ") + e.what());
  }
}

void parseNoise(const Ctx& c, const toml::table& t, NoiseConfig& n) {
  struct F {
    std::string_view name;
    double NoiseConfig::*field;
    double hi;
  };
  static const F fields[] = {
      {"ibv_v", &NoiseConfig::ibv_v, 5.0},         {"bcur_a", &NoiseConfig::bcur_a, 100.0},
      {"battery_v", &NoiseConfig::battery_v, 5.0}, {"alt_a", &NoiseConfig::alt_a, 100.0},
      {"rpm", &NoiseConfig::rpm, 1000.0},          {"temp_f", &NoiseConfig::temp_f, 50.0}};
  for (auto&& [k, v] : t) {
    bool found = false;
    for (const auto& f : fields) {
      if (k.str() == f.name) {
        n.*(f.field) = number(c, k, v, 0.0, f.hi);
        found = true;
      }
    }
    if (!found) unknownKey(c, k, "[noise]");
  }
}

}  // namespace xr::sim::scenario_toml
