#pragma once
// The scenario loader's TOML reading helpers, shared by the scenario file's
// parts (scenario.cpp: events, config, top level; scenario_plant.cpp: the
// plant sections). Every error names file:line: (exit 64).
#include <toml++/toml.h>

#include <string>
#include <string_view>
#include <vector>

#include "drivers/sim/scenario.h"

namespace xr::sim::scenario_toml {

struct Ctx {
  std::string src;
  [[noreturn]] void fail(int line, const std::string& msg) const {
    throw ScenarioError(src + ":" + std::to_string(line) + ": " + msg);
  }
};

int lineOf(const toml::node& n);
int lineOf(const toml::key& k);
double number(const Ctx& c, const toml::key& k, const toml::node& v, double lo, double hi);
std::vector<double> numbers(const Ctx& c, const toml::key& k, const toml::node& v, double lo, double hi);
std::string text(const Ctx& c, const toml::key& k, const toml::node& v);
const toml::table& tableOf(const Ctx& c, const toml::key& k, const toml::node& v);
[[noreturn]] void unknownKey(const Ctx& c, const toml::key& k, std::string_view where);

// The plant sections (scenario_plant.cpp).
void parseBattery(const Ctx& c, const toml::table& t, BatteryConfig& b);
void parseAlternator(const Ctx& c, const toml::table& t, AlternatorConfig& a);
void parseNoise(const Ctx& c, const toml::table& t, NoiseConfig& n);
// [bms] and the bms_* event keys (scenario_bms.cpp). parseBmsEventKey
// returns false when `k` is not one of its keys.
void parseBms(const Ctx& c, const toml::table& t, ScenarioBms& b);
bool parseBmsEventKey(const Ctx& c, const toml::key& k, const toml::node& v, ScenarioEvent& e);
// [gps] and [weather] (scenario_position.cpp).
void parseGps(const Ctx& c, const toml::table& t, ScenarioGps& g);
void parseWeather(const Ctx& c, const toml::table& t, ScenarioWeather& w);
// [solar], [charger] and the [loads] keys (scenario_sources.cpp);
// parseLoadKey returns false when `k` is not one of [loads]' keys.
void parseChargeSource(const Ctx& c, const toml::table& t, ChargeSourceConfig& s, bool solar);
bool parseLoadKey(const Ctx& c, const toml::key& k, const toml::node& v, PlantConfig& p);
// An event that changes the simulated BMS or engine ECU in a scenario
// without one.
void checkBmsEvents(const Ctx& c, const Scenario& s);

}  // namespace xr::sim::scenario_toml
