#include "config/config.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <map>
#include <ostream>

#include "config/battery_profiles.h"
#include "config/bounded_read.h"
#include "config/format.h"
#include "config/hardware_choices.h"
#include "config/integration_checks.h"
#include "config/param_values.h"
#include "config/settings_schema.h"
#include "config/toml_text_guard.h"
#include "config/toml_values.h"
#include "config/web_checks.h"
#include "params/derived.h"

namespace xr {

std::string ConfigError::toString() const {
  std::string s = file;
  if (line > 0) {
    s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
  }
  s += ": ";
  if (!key.empty()) s += key + ": ";
  return s + message;
}

namespace {

struct Location {
  int line = 0;
  int column = 0;
};

Location where(const toml::source_region& r) {
  return {static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
}

// Closest of candidates to word, or empty when none is a plausible typo.
template <class Range>
std::string closest(std::string_view word, const Range& candidates) {
  std::string best;
  std::size_t bestD = std::string::npos;
  for (std::string_view c : candidates) {
    const auto d = editDistance(word, c);
    if (d < bestD) {
      bestD = d;
      best = std::string(c);
    }
  }
  return bestD <= std::max<std::size_t>(2, word.size() / 3) ? best : std::string{};
}

const ParamGroup kGroups[] = {ParamGroup::Voltage,  ParamGroup::Overvoltage, ParamGroup::SensorHealth,
                              ParamGroup::Shutdown, ParamGroup::Current,     ParamGroup::Tuning,
                              ParamGroup::Charging, ParamGroup::Battery,     ParamGroup::Temperature,
                              ParamGroup::Alarms,   ParamGroup::Modes,       ParamGroup::Can,
                              ParamGroup::RpmTables};

std::optional<ParamGroup> groupForTable(std::string_view table) {
  for (auto g : kGroups)
    if (tomlTableName(g) == table) return g;
  return std::nullopt;
}

// A settings table, or the parent of dotted ones ("integrations").
bool isSettingsTableOrParent(std::string_view name) {
  for (auto t : settingsTables())
    if (t == name || (t.size() > name.size() && t.starts_with(name) && t[name.size()] == '.')) return true;
  return false;
}

std::vector<std::string> allTableNames() {
  std::vector<std::string> t;
  for (auto g : kGroups) t.emplace_back(tomlTableName(g));
  for (auto s : settingsTables()) t.emplace_back(s);
  return t;
}

class Loader {
 public:
  explicit Loader(std::string_view file) : file_(file) {}

  LoadResult run(std::string_view text) {
    if (const auto bad = tomlTextProblem(text)) {  // never handed to toml++ (toml_text_guard.h)
      result_.errors.push_back({file_, bad->line, bad->column, "", std::string(bad->message)});
      return std::move(result_);
    }
    toml::table root;
    try {
      root = toml::parse(text, file_);
    } catch (const toml::parse_error& e) {
      const auto loc = where(e.source());
      result_.errors.push_back(
          {file_, loc.line, loc.column, "", "TOML syntax error: " + std::string(e.description())});
      return std::move(result_);
    }
    for (auto&& [k, node] : root) topLevel(k, node);
    // The battery profile fills what the file did not set (docs/batteries.md).
    {
      ProfileApplied pa = applyBatteryProfile(config_.params, config_.fileParamNames);
      config_.params = pa.params;
      config_.profileParamNames = std::move(pa.setByProfile);
    }
    followRaisedTemperatureLimit();

    for (auto& e : checkConsistency(config_.params, file_)) {
      // Point consistency errors at the key in the file when it was written there.
      if (auto it = paramLoc_.find(e.key); it != paramLoc_.end()) {
        e.line = it->second.line;
        e.column = it->second.column;
      }
      result_.errors.push_back(std::move(e));
    }
    settingsConsistency();

    std::stable_sort(result_.errors.begin(), result_.errors.end(),
                     [](const ConfigError& a, const ConfigError& b) {
                       const int la = a.line == 0 ? INT32_MAX : a.line;
                       const int lb = b.line == 0 ? INT32_MAX : b.line;
                       return la != lb ? la < lb : a.column < b.column;
                     });
    if (result_.errors.empty()) result_.config = config_;
    return std::move(result_);
  }

 private:
  // Older shipped files wrote TempAlarm = 190 beside TemperatureLimitF = 150.
  // Raising the limit to or past that alarm must not stop an installed
  // regulator at the next start: the alarm follows the limit instead (its
  // 0), and the start log says so (docs/configuration.md "Derived values").
  void followRaisedTemperatureLimit() {
    Params& p = config_.params;
    if (!config_.fileParamNames.count("TempAlarm") || p.TempAlarm <= 0.0 || p.TempAlarm > p.TemperatureLimitF)
      return;
    config_.notices.push_back("TempAlarm " + formatNumber(p.TempAlarm) +
                              " degF in the file is not above TemperatureLimitF " +
                              formatNumber(p.TemperatureLimitF) + " degF: the alarm follows the limit at " +
                              formatNumber(p.TemperatureLimitF + kTempAlarmDerivedMarginF) +
                              " degF; delete the TempAlarm line to silence this");
    p.TempAlarm = 0.0;
    config_.fileParamNames.erase("TempAlarm");
  }

  void error(const toml::key& k, std::string key, std::string message) {
    const auto loc = where(k.source());
    result_.errors.push_back({file_, loc.line, loc.column, std::move(key), std::move(message)});
  }

  void topLevel(const toml::key& k, const toml::node& node) {
    const std::string name(k.str());
    if (auto g = groupForTable(name)) {
      if (const auto* t = node.as_table()) return paramTable(*g, name, *t);
      return error(k, name, "must be a table: write [" + name + "] and put its parameters below it");
    }
    if (isSettingsTableOrParent(name)) {
      if (const auto* t = node.as_table()) return settingsTable(name, *t);
      return error(k, name, "must be a table: write [" + name + "]");
    }
    if (const auto* spec = findParam(name))
      return error(k, name,
                   "parameters live in their group table: put " + name + " under [" +
                       std::string(tomlTableName(spec->group)) + "]");
    std::string msg = "unknown table or key";
    const auto tables = allTableNames();
    std::string near = closest(name, tables);
    if (near.empty()) near = closestParamName(name);
    if (!near.empty()) msg += " (did you mean " + near + "?)";
    error(k, name, msg);
  }

  void paramTable(ParamGroup group, const std::string& table, const toml::table& t) {
    for (auto&& [k, node] : t) {
      const std::string name(k.str());
      const std::string dotted = table + "." + name;
      const ParamSpec* spec = findParam(name);
      // [can] holds both parameters and settings (the interfaces, the protocol).
      if (!spec && findSetting(table, name)) {
        settingKey(table, k, node);
        continue;
      }
      if (!spec) {
        std::string msg = "unknown parameter";
        if (auto near = closestParamName(name); !near.empty()) {
          msg += " (did you mean " + near;
          if (const auto* s = findParam(near); s->group != group)
            msg += ", in [" + std::string(tomlTableName(s->group)) + "]";
          msg += "?)";
        }
        error(k, dotted, msg);
        continue;
      }
      if (spec->group != group) {
        error(k, dotted,
              name + " belongs in [" + std::string(tomlTableName(spec->group)) + "], not [" + table + "]");
        continue;
      }
      paramLoc_[dotted] = where(k.source());
      auto v = detail::paramValueFromNode(*spec, node);
      if (auto* why = std::get_if<std::string>(&v)) {
        error(k, dotted, *why);
        continue;
      }
      setParamValue(config_.params, *spec, std::get<ParamValue>(v));
      config_.fileParamNames.insert(name);
    }
  }

  void settingsTable(const std::string& table, const toml::table& t) {
    for (auto&& [k, node] : t) {
      const std::string name(k.str());
      const std::string dotted = table + "." + name;
      if (isSettingsTableOrParent(dotted)) {  // [hardware.frontend], [integrations.mqtt], ...
        if (const auto* sub = node.as_table()) {
          settingsTable(dotted, *sub);
        } else {
          error(k, dotted, "must be a table: write [" + dotted + "]");
        }
        continue;
      }
      const SettingSpec* spec = findSetting(table, name);
      if (spec) {
        settingKey(table, k, node);
        continue;
      }
      {
        std::vector<std::string_view> keys;
        for (const auto& s : settingsSchema())
          if (s.table == table) keys.push_back(s.key);
        std::string msg = "unknown setting";
        if (const char* why = retiredSetting(dotted))
          msg = why;
        else if (auto near = closest(name, keys); !near.empty())
          msg += " (did you mean " + near + "?)";
        else if (const auto* p = findParam(name))
          msg +=
              " (" + name + " is a parameter: put it under [" + std::string(tomlTableName(p->group)) + "])";
        error(k, dotted, msg);
      }
    }
  }

  // One known setting: its value checked and stored.
  void settingKey(const std::string& table, const toml::key& k, const toml::node& node) {
    const std::string dotted = table + "." + std::string(k.str());
    const SettingSpec* spec = findSetting(table, k.str());
    settingLoc_[dotted] = where(k.source());
    auto v = detail::settingValueFromNode(*spec, node);
    if (auto* why = std::get_if<std::string>(&v)) return error(k, dotted, *why);
    spec->set(config_.settings, std::get<SettingValue>(v));
  }

  // The field enable must be a real line of its own: sharing it with the
  // buzzer or an input would make "field LOW" impossible to guarantee.
  void settingsConsistency() {
    const auto& h = config_.settings.hardware;
    const std::pair<const char*, int> others[] = {{"buzzer_line", h.buzzer_line},
                                                  {"bms_line", h.bms_line},
                                                  {"ignition_line", h.ignition_line},
                                                  {"ads_alert_rdy_line", h.ads_alert_rdy_line}};
    for (const auto& [name, line] : others) {
      if (line >= 0 && line == h.field_enable_line) {
        settingError("hardware." + std::string(name),
                     "uses GPIO line " + std::to_string(line) + ", which is already the field_enable_line");
      }
    }
    pairingButtonLine();
    webSettings();
    for (auto& [key, message] : checkIntegrations(config_.settings.integrations, config_.settings.can))
      settingError(key, message);
    for (auto& [key, message] : checkCan(config_.settings.can)) settingError(key, message);
    for (auto& [key, message] : checkBatteryProbe(config_.settings.hardware)) settingError(key, message);
  }

  // The pairing button needs a line of its own: libgpiod grants a line once,
  // and the field enable must never be an input.
  void pairingButtonLine() {
    const auto& h = config_.settings.hardware;
    const int button = config_.settings.pairing.button_line;
    if (button < 0) return;
    const std::pair<const char*, int> lines[] = {{"field_enable_line", h.field_enable_line},
                                                 {"buzzer_line", h.buzzer_line},
                                                 {"bms_line", h.bms_line},
                                                 {"ignition_line", h.ignition_line},
                                                 {"ads_alert_rdy_line", h.ads_alert_rdy_line}};
    for (const auto& [name, line] : lines)
      if (line == button)
        settingError("pairing.button_line",
                     "uses GPIO line " + std::to_string(line) + ", which is already [hardware] " + name);
  }

  void settingError(const std::string& key, std::string message) {
    ConfigError e{file_, 0, 0, key, std::move(message)};
    if (auto it = settingLoc_.find(key); it != settingLoc_.end()) {
      e.line = it->second.line;
      e.column = it->second.column;
    }
    result_.errors.push_back(std::move(e));
  }

  // [web] is checked here, not first discovered by the web server at run
  // time: there a failure can only mean running without the dashboard
  // (docs/security.md).
  void webSettings() {
    const auto& w = config_.settings.web;
    if (!isNumericListenAddress(w.listen))
      settingError("web.listen",
                   "'" + w.listen +
                       "' is not an IP address: write an IPv4 or IPv6 address such as "
                       "\"127.0.0.1\" (this machine only), \"0.0.0.0\" (every interface) or \"::\"");
    if (auto why = checkTokenText(w.token); !why.empty()) settingError("web.token", why);
  }

  std::string file_;
  Config config_;
  LoadResult result_;
  std::map<std::string, Location> paramLoc_;
  std::map<std::string, Location> settingLoc_;
};

}  // namespace

LoadResult loadConfigString(std::string_view text, std::string_view name) { return Loader(name).run(text); }

LoadResult loadConfigFile(const std::string& path) {
  std::string text;
  if (std::string why = readConfigText(path, text); !why.empty()) {
    LoadResult r;
    r.errors.push_back({path, 0, 0, "", why});
    return r;
  }
  return loadConfigString(text, path);
}

int checkConfigMain(const std::string& path, std::ostream& out, std::ostream& err) {
  const LoadResult r = loadConfigFile(path);
  if (r.ok()) {
    const auto changed = overridesFromDefaults(r.config->params).size();
    out << path << ": OK (" << catalogue().size() << " parameters, " << changed
        << " differ from the defaults)\n";
    return 0;
  }
  for (const auto& e : r.errors) err << e.toString() << "\n";
  err << path << ": " << r.errors.size() << (r.errors.size() == 1 ? " error" : " errors")
      << "; xregulatord will not start with this configuration\n";
  return kExitConfig;
}

}  // namespace xr
