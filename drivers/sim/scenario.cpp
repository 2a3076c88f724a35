#include "drivers/sim/scenario.h"

#include <toml++/toml.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "config/toml_text_guard.h"
#include "drivers/sim/scenario_toml.h"

namespace xr::sim {
using namespace scenario_toml;

namespace {

// Parameter overrides: [config] and set = { ... }.
ParamOverride paramOverride(const Ctx& c, const toml::key& k, const toml::node& v) {
  ParamOverride o;
  o.name = std::string(k.str());
  o.line = lineOf(k);
  const ParamSpec* spec = findParam(o.name);
  if (!spec) c.fail(o.line, "unknown parameter '" + o.name + "'");
  auto one = [&](const toml::node& n) {
    double d;
    if (n.is_string() && !spec->choices.empty()) {
      // A named choice ("lifepo4"), as in xregulator.toml.
      const auto idx = choiceIndex(*spec, *n.value<std::string>());
      if (!idx) c.fail(lineOf(n), "parameter '" + o.name + "' must be one of " + std::string(spec->choices));
      d = *idx;
    } else if (n.is_boolean())
      d = *n.value<bool>() ? 1.0 : 0.0;
    else if (n.is_integer() || n.is_floating_point())
      d = *n.value<double>();
    else
      c.fail(lineOf(n), "parameter '" + o.name + "' needs a number");
    if (!valueFits(*spec, d)) {
      std::ostringstream m;
      m << "parameter '" << o.name << "' = " << d << " is out of range [" << spec->min << ", " << spec->max
        << "]";
      if (spec->kind == ParamKind::Int || spec->kind == ParamKind::Bool) m << " or not a whole number";
      c.fail(lineOf(n), m.str());
    }
    o.values.push_back(d);
  };
  if (spec->kind == ParamKind::Table) {
    const toml::array* a = v.as_array();
    if (!a || a->size() != RPM_TABLE_SIZE)
      c.fail(lineOf(v),
             "parameter '" + o.name + "' needs an array of " + std::to_string(RPM_TABLE_SIZE) + " numbers");
    for (const auto& n : *a) one(n);
  } else {
    one(v);
  }
  return o;
}

// An [[events]] command with its argument (`duty`, `soc_pct` or `active`).
Command eventCommand(const Ctx& c, CommandType type, const std::string& argName, const toml::node* arg,
                     int cmdLine) {
  Command command;
  command.type = type;
  if (argName.empty()) return command;
  if (!arg) c.fail(cmdLine, "command '" + std::string(toString(type)) + "' needs " + argName + " = ...");
  if (argName == "active") {
    if (!arg->is_boolean()) c.fail(lineOf(*arg), "'active' must be true or false");
    command.flag = *arg->value<bool>();
    return command;
  }
  std::optional<double> d;
  if (arg->is_integer() || arg->is_floating_point()) d = arg->value<double>();
  if (!d || !(*d >= 0.0 && *d <= 100.0))
    c.fail(lineOf(*arg), "'" + argName + "' must be a number in [0, 100]");
  command.value = *d;
  return command;
}

// A fault and its value go together, and a fault is injected or cleared, not both.
void checkEventFault(const Ctx& c, const ScenarioEvent& e, bool haveValue) {
  if (e.fault && e.clear) c.fail(e.line, "an event cannot both inject and clear a fault");
  if (e.fault && faultTakesValue(*e.fault) && !haveValue)
    c.fail(e.line, "fault '" + std::string(toString(*e.fault)) + "' needs value = ...");
  if (haveValue && !(e.fault && faultTakesValue(*e.fault)))
    c.fail(e.line, "'value' only goes with a fault that takes one");
  if (e.fault && *e.fault == Fault::temp_value && (e.value < -60.0 || e.value > 400.0))
    c.fail(e.line, "temp_value must be within [-60, 400] degF");
}

// The events that move a line or a switch, each to one of two words.
bool parseLevelEventKey(const Ctx& c, const toml::key& k, const toml::node& v, ScenarioEvent& e) {
  struct Level {
    std::string_view key, yes, no;
    std::optional<bool> ScenarioEvent::*field;
  };
  static constexpr Level kLevels[] = {
      {"ignition", "on", "off", &ScenarioEvent::ignition},
      {"pairing_button", "pressed", "released", &ScenarioEvent::pairing_button},
      {"bms", "connect", "disconnect", &ScenarioEvent::bms_connected},
      {"bms_input", "charge_enabled", "charge_disabled", &ScenarioEvent::bms_charge_enabled},
      {"charger", "on", "off", &ScenarioEvent::charger_on},
  };
  for (const auto& l : kLevels) {
    if (k.str() != l.key) continue;
    const auto s = text(c, k, v);
    if (s != l.yes && s != l.no)
      c.fail(lineOf(v),
             std::string(l.key) + " must be \"" + std::string(l.yes) + "\" or \"" + std::string(l.no) + "\"");
    e.*l.field = s == l.yes;
    return true;
  }
  return false;
}

ScenarioEvent parseEvent(const Ctx& c, const toml::table& t, double duration) {
  ScenarioEvent e;
  e.line = lineOf(t);
  bool haveAt = false, haveValue = false;
  std::optional<CommandType> cmd;
  const toml::node* cmdArg = nullptr;
  int cmdLine = e.line;
  std::string cmdArgName;
  // The command's argument key is only known after reading `command`.
  if (auto* cn = t.get("command")) {
    const auto s = cn->value<std::string>();
    if (!s) c.fail(lineOf(*cn), "'command' must be a string");
    cmd = parseCommandType(*s);
    if (!cmd) c.fail(lineOf(*cn), "unknown command '" + *s + "'");
    cmdLine = lineOf(*cn);
    cmdArgName = std::string(commandArgument(*cmd));
  }
  for (auto&& [k, v] : t) {
    const auto n = k.str();
    if (n == "at_s") {
      e.at_s = number(c, k, v, 0.0, duration);
      haveAt = true;
    } else if (n == "rpm") {
      e.rpm = number(c, k, v, 0.0, 10000.0);
    } else if (n == "house_a") {
      e.house_a = number(c, k, v, 0.0, 2000.0);
    } else if (n == "ambient_f") {
      e.ambient_f = number(c, k, v, -40.0, 200.0);
    } else if (n == "battery_temp_c") {
      e.battery_temp_c = number(c, k, v, -40.0, 80.0);
    } else if (parseLevelEventKey(c, k, v, e)) {
    } else if (parseBmsEventKey(c, k, v, e)) {
    } else if (n == "command") {
      // handled above
    } else if (!cmdArgName.empty() && n == cmdArgName) {
      cmdArg = &v;
    } else if (n == "set") {
      const toml::table& st = tableOf(c, k, v);
      if (st.empty()) c.fail(lineOf(v), "'set' is empty");
      for (auto&& [pk, pv] : st) e.set.push_back(paramOverride(c, pk, pv));
    } else if (n == "fault" || n == "clear") {
      const auto s = text(c, k, v);
      const auto f = parseFault(s);
      if (!f) c.fail(lineOf(v), "unknown fault '" + s + "'");
      (n == "fault" ? e.fault : e.clear) = *f;
    } else if (n == "value") {
      e.value = number(c, k, v, -1000.0, 1000.0);
      haveValue = true;
    } else {
      unknownKey(c, k, "[[events]]");
    }
  }
  if (!haveAt) c.fail(e.line, "event without at_s");
  checkEventFault(c, e, haveValue);
  if (cmd) e.command = eventCommand(c, *cmd, cmdArgName, cmdArg, cmdLine);
  const bool any = e.rpm || e.house_a || e.ambient_f || e.battery_temp_c || e.ignition || e.pairing_button ||
                   e.bms_connected || e.bms_charge_enabled || e.charger_on || e.touchesSimCan() ||
                   e.command || !e.set.empty() || e.fault || e.clear;
  if (!any) c.fail(e.line, "event does nothing");
  return e;
}

// [[events]], in time order.
void parseEvents(const Ctx& c, const toml::node& v, Scenario& s) {
  const toml::array* a = v.as_array();
  if (!a) c.fail(lineOf(v), "'events' must be an array of tables ([[events]])");
  double last = 0.0;
  for (const auto& en : *a) {
    if (!en.is_table()) c.fail(lineOf(en), "each event must be a table");
    ScenarioEvent e = parseEvent(c, *en.as_table(), s.duration_s);
    if (e.at_s < last) {
      std::ostringstream m;
      m << "events out of order: at_s = " << e.at_s << " comes after at_s = " << last;
      c.fail(e.line, m.str());
    }
    last = e.at_s;
    s.events.push_back(std::move(e));
  }
}

Scenario parseTable(const Ctx& c, const toml::table& root) {
  Scenario s;
  s.source = c.src;
  // duration first: events are checked against it.
  if (auto* d = root.get("duration_s")) {
    toml::key k("duration_s");
    s.duration_s = number(c, k, *d, 0.001, 1.0e7);
  }
  for (auto&& [k, v] : root) {
    const auto n = k.str();
    if (n == "name") {
      s.name = text(c, k, v);
    } else if (n == "duration_s") {
    } else if (n == "seed") {
      if (!v.is_integer() || *v.value<std::int64_t>() < 0)
        c.fail(lineOf(v), "'seed' must be a non-negative integer");
      s.seed = std::uint64_t(*v.value<std::int64_t>());
    } else if (n == "set_up") {
      if (!v.is_boolean()) c.fail(lineOf(v), "'set_up' must be true or false");
      s.set_up = *v.value<bool>();
    } else if (n == "config") {
      for (auto&& [pk, pv] : tableOf(c, k, v)) s.config.push_back(paramOverride(c, pk, pv));
    } else if (n == "battery") {
      parseBattery(c, tableOf(c, k, v), s.plant.battery);
    } else if (n == "alternator") {
      parseAlternator(c, tableOf(c, k, v), s.plant.alternator);
    } else if (n == "engine") {
      for (auto&& [ek, ev] : tableOf(c, k, v)) {
        if (ek.str() == "rpm") {
          s.plant.rpm = number(c, ek, ev, 0.0, 10000.0);
        } else if (ek.str() == "ecu") {
          if (!ev.is_boolean()) c.fail(lineOf(ev), "[engine] ecu must be true or false");
          s.engine_ecu = *ev.value<bool>();
        } else {
          unknownKey(c, ek, "[engine]");
        }
      }
    } else if (n == "loads") {
      for (auto&& [lk, lv] : tableOf(c, k, v)) {
        if (!parseLoadKey(c, lk, lv, s.plant)) unknownKey(c, lk, "[loads]");
      }
    } else if (n == "bus") {
      for (auto&& [bk, bv] : tableOf(c, k, v)) {
        if (bk.str() == "capacitance_f")
          s.plant.bus_capacitance_f = number(c, bk, bv, 1e-5, 10.0);
        else if (bk.str() == "tvs_clamp_v")
          s.plant.tvs_clamp_v = number(c, bk, bv, 0.0, 200.0);
        else
          unknownKey(c, bk, "[bus]");
      }
    } else if (n == "solar" || n == "charger") {
      parseChargeSource(c, tableOf(c, k, v), n == "solar" ? s.plant.solar : s.plant.charger, n == "solar");
    } else if (n == "bms") {
      parseBms(c, tableOf(c, k, v), s.bms);
    } else if (n == "gps") {
      parseGps(c, tableOf(c, k, v), s.gps);
    } else if (n == "weather") {
      parseWeather(c, tableOf(c, k, v), s.weather.emplace());
    } else if (n == "noise") {
      parseNoise(c, tableOf(c, k, v), s.noise);
    } else if (n == "events") {
      parseEvents(c, v, s);
    } else {
      unknownKey(c, k, "");
    }
  }
  checkBmsEvents(c, s);
  for (const auto& e : s.events)
    if (e.charger_on && !s.plant.charger.present) c.fail(e.line, "'charger' event without a [charger]");
  if (s.name.empty()) s.name = c.src;
  return s;
}

}  // namespace

Scenario parseScenario(std::string_view text, std::string_view sourceName) {
  Ctx c{std::string(sourceName)};
  if (const auto bad = tomlTextProblem(text))  // never handed to toml++ (toml_text_guard.h)
    throw ScenarioError(c.src + ":" + std::to_string(bad->line) + ":" + std::to_string(bad->column) + ": " +
                        std::string(bad->message));
  toml::table root;
  try {
    root = toml::parse(text, sourceName);
  } catch (const toml::parse_error& e) {
    c.fail(int(e.source().begin.line), "syntax error: " + std::string(e.description()));
  }
  return parseTable(c, root);
}

Scenario loadScenario(const std::filesystem::path& file) {
  std::ifstream f(file, std::ios::binary);
  if (!f) throw ScenarioError(file.string() + ":0: cannot open scenario file");
  std::ostringstream ss;
  ss << f.rdbuf();
  return parseScenario(ss.str(), file.string());
}

Scenario defaultScenario() {
  Scenario s;
  s.name = "default: LiFePO4 400 Ah from 35 %, cruise 1800 rpm";
  s.source = "<built-in>";
  s.duration_s = 8 * 3600.0;
  s.plant.battery.chemistry = Chemistry::lifepo4;
  s.plant.battery.capacity_ah = 400.0;
  s.plant.battery.soc_pct = 35.0;
  return s;
}

void applyOverrides(Params& p, const std::vector<ParamOverride>& o, std::string_view source) {
  for (const auto& x : o) {
    const ParamSpec* spec = findParam(x.name);
    if (!spec)
      throw ScenarioError(std::string(source) + ":" + std::to_string(x.line) + ": unknown parameter '" +
                          x.name + "'");
    for (std::size_t i = 0; i < x.values.size(); ++i) {
      if (!valueFits(*spec, x.values[i]))
        throw ScenarioError(std::string(source) + ":" + std::to_string(x.line) + ": bad value for '" +
                            x.name + "'");
      spec->set(p, i, x.values[i]);
    }
  }
}

void ScenarioPlayer::applyToWorld(const ScenarioEvent& e, SimWorld& w) {
  if (e.rpm) w.plant().setRpm(*e.rpm);
  if (e.house_a) w.plant().setHouseAmps(*e.house_a);
  if (e.ambient_f) w.plant().setAmbientF(*e.ambient_f);
  if (e.battery_temp_c) w.plant().setBatteryTempC(*e.battery_temp_c);
  if (e.ignition) w.setIgnition(*e.ignition);
  if (e.pairing_button) w.setPairingButton(*e.pairing_button);
  if (e.bms_connected) w.plant().setBmsConnected(*e.bms_connected);
  if (e.bms_charge_enabled) w.setBmsChargeEnabled(*e.bms_charge_enabled);
  if (e.charger_on) w.plant().setChargerOn(*e.charger_on);
  if (e.fault) w.setFault(*e.fault, true, e.value);
  if (e.clear) w.setFault(*e.clear, false);
}

}  // namespace xr::sim
