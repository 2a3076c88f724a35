// xr_gendocs: writes config/xregulator.toml and docs/parameters.md from the
// parameter catalogue and the settings schema, so neither is ever edited by
// hand ("No parameter is spelled out by hand in more than one place").
//
//   xr_gendocs toml                print the default configuration file
//   xr_gendocs markdown            print docs/parameters.md
//   xr_gendocs write ROOT          write both into the source tree at ROOT
//   xr_gendocs check ROOT          exit 1 when a committed file is stale
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "config/format.h"
#include "config/settings_schema.h"
#include "params/params.h"

namespace {

using namespace xr;

constexpr ParamGroup kGroups[] = {ParamGroup::Voltage,  ParamGroup::Overvoltage, ParamGroup::SensorHealth,
                                  ParamGroup::Shutdown, ParamGroup::Current,     ParamGroup::Tuning,
                                  ParamGroup::Charging, ParamGroup::Battery,     ParamGroup::Temperature,
                                  ParamGroup::Alarms,   ParamGroup::Modes,       ParamGroup::Can,
                                  ParamGroup::RpmTables};

// Word-wrapped "# " comment lines.
void comment(std::ostream& o, std::string_view text, std::size_t width = 88) {
  std::string line;
  std::istringstream words{std::string(text)};
  std::string w;
  while (words >> w) {
    if (!line.empty() && line.size() + 1 + w.size() + 2 > width) {
      o << "# " << line << "\n";
      line.clear();
    }
    if (!line.empty()) line += ' ';
    line += w;
  }
  if (!line.empty()) o << "# " << line << "\n";
}

// TOML float literal: always with a '.' or exponent so the type is visible.
std::string tomlFloat(double v) {
  std::string s = formatNumber(v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string tomlString(std::string_view s) {
  std::string r = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') r += '\\';
    r += c;
  }
  return r + "\"";
}

std::string paramDefault(const ParamSpec& s, bool toml) {
  if (!s.choices.empty()) return tomlString(std::string(choiceName(s, static_cast<int>(s.defaultValue))));
  switch (s.kind) {
    case ParamKind::Float:
      return toml ? tomlFloat(s.defaultValue) : formatNumber(s.defaultValue);
    case ParamKind::Int:
      return formatNumber(s.defaultValue);
    case ParamKind::Bool:
      return s.defaultValue != 0.0 ? "true" : "false";
    case ParamKind::Table: {
      std::string r = "[";
      for (std::size_t i = 0; i < RPM_TABLE_SIZE; ++i) {
        if (i) r += ", ";
        r += toml ? tomlFloat(s.tableDefault[i]) : formatNumber(s.tableDefault[i]);
      }
      return r + "]";
    }
  }
  return "?";
}

std::string paramRange(const ParamSpec& s) {
  if (s.kind == ParamKind::Bool) return "true/false (or 1/0)";
  if (!s.choices.empty()) return "one of " + std::string(s.choices);
  std::string r = formatNumber(s.min) + " to " + formatNumber(s.max);
  if (s.kind == ParamKind::Int) r += ", whole";
  if (s.kind == ParamKind::Table) r = std::to_string(RPM_TABLE_SIZE) + " values, each " + r;
  return r;
}

std::string settingDefault(const SettingSpec& s) {
  const SettingValue v = s.get(Settings{});
  switch (s.kind) {
    case SettingKind::String:
      return tomlString(std::get<std::string>(v));
    case SettingKind::Bool:
      return std::get<bool>(v) ? "true" : "false";
    case SettingKind::Float:
      return tomlFloat(std::get<double>(v));
    case SettingKind::Int: {
      const auto i = std::get<std::int64_t>(v);
      if (!s.hex) return std::to_string(i);
      std::ostringstream o;
      o << "0x" << std::hex << i;
      return o.str();
    }
    case SettingKind::IntList: {
      std::string r = "[";
      const auto& l = std::get<std::vector<std::int64_t>>(v);
      for (std::size_t i = 0; i < l.size(); ++i) r += (i ? ", " : "") + std::to_string(l[i]);
      return r + "]";
    }
  }
  return "?";
}

std::string settingRange(const SettingSpec& s) {
  switch (s.kind) {
    case SettingKind::String:
      return s.choices.empty() ? "text" : "one of " + std::string(s.choices);
    case SettingKind::Bool:
      return "true/false";
    case SettingKind::IntList:
      return "list of " + formatNumber(s.min) + " to " + formatNumber(s.max);
    case SettingKind::Int:
    case SettingKind::Float: {
      std::string r = formatNumber(s.min) + " to " + formatNumber(s.max);
      if (!s.unit.empty()) r += " " + std::string(s.unit);
      return r;
    }
  }
  return "";
}

// What an installer must decide (docs/configuration.md "One chain of
// values"): written as live keys. Everything else is written commented out,
// so the shipped file pins nothing the profile or the dashboard should set.
bool installerParam(std::string_view name) {
  // BatteryProfile is left commented: naming it is what sets the regulator
  // up (docs/configuration.md "Not set up").
  return name == "BatteryCells" || name == "BatteryCapacity_Ah";
}
bool installerSetting(std::string_view table, std::string_view key) {
  return table == "hardware" || table == "hardware.frontend" ||
         (table == "web" && (key == "listen" || key == "port"));
}

std::string tomlText() {
  std::ostringstream o;
  o << "# xregulator.toml - configuration of xregulatord, the alternator field regulator.\n"
       "#\n"
       "# GENERATED by tools/xr_gendocs from the parameter catalogue\n"
       "# (daemon/params/catalogue.def) and the settings schema\n"
       "# (daemon/config/settings_schema.cpp). Do not edit the copy in the source tree:\n"
       "# change those, then run `cmake --build build --target regen-docs`.\n"
       "#\n"
       "# Every key is optional. The ones an installer must decide are set: the battery\n"
       "# type and size, the hardware lines and the web address. Every other key is\n"
       "# here commented out with its default, so it documents without pinning: the\n"
       "# battery profile and the dashboard can still set it. Uncomment a key to fix it\n"
       "# here; a value in this file wins over the profile (docs/configuration.md).\n"
       "# Check an edited file with `xregulatord --config FILE --check-config`\n"
       "# (exit 0 = OK, 78 = errors, all of them listed with file:line:column).\n"
       "# Parameter names are the specification's names and each is unique across tables.\n"
       "#\n"
       "# A wrong voltage or current limit can destroy an alternator or a battery bank.\n"
       "# Change one value at a time and watch the result on the dashboard.\n";
  o << "\n# ============================================================ parameters\n";
  for (auto g : kGroups) {
    o << "\n[" << tomlTableName(g) << "]\n";
    for (const auto& s : catalogue()) {
      if (s.group != g) continue;
      o << "\n";
      comment(o, s.help);
      std::string meta = paramRange(s);
      if (!s.unit.empty()) meta += " " + std::string(s.unit);
      comment(o, meta + ". Default " + paramDefault(s, false) + ".");
      o << (installerParam(s.name) ? "" : "# ") << s.name << " = " << paramDefault(s, true) << "\n";
    }
    // A table that holds settings beside its parameters ([can]).
    for (const auto& s : settingsSchema()) {
      if (s.table != tomlTableName(g)) continue;
      o << "\n";
      comment(o, s.help);
      comment(o, settingRange(s) + ".");
      o << (installerSetting(s.table, s.key) ? "" : "# ") << s.key << " = " << settingDefault(s) << "\n";
    }
  }
  o << "\n# ============================================================ settings\n";
  for (auto table : settingsTables()) {
    o << "\n[" << table << "]\n";
    for (const auto& s : settingsSchema()) {
      if (s.table != table) continue;
      o << "\n";
      comment(o, s.help);
      comment(o, settingRange(s) + ".");
      o << (installerSetting(s.table, s.key) ? "" : "# ") << s.key << " = " << settingDefault(s) << "\n";
    }
  }
  return o.str();
}

std::string mdCell(std::string_view s) {
  std::string r;
  for (char c : s) {
    if (c == '|')
      r += "\\|";
    else
      r += c;
  }
  return r;
}

std::string markdownText() {
  std::ostringstream o;
  o << "# Parameters\n\n"
       "<!-- GENERATED by tools/xr_gendocs from daemon/params/catalogue.def and\n"
       "     daemon/config/settings_schema.cpp. Do not edit: run\n"
       "     `cmake --build build --target regen-docs`. A test fails when this file is stale. -->\n\n"
       "Every user-settable parameter of xregulatord, by the table it lives in in\n"
       "`/etc/xregulator/xregulator.toml`. Names are the specification's names. The same names are\n"
       "used by the HTTP API (`GET`/`PATCH /api/params`) and by a scenario's `[config]`\n"
       "table. Booleans accept `true`/`false` or `1`/`0`. RPM tables hold "
    << RPM_TABLE_SIZE
    << " values,\none per breakpoint of `rpmTableRPMPoints`.\n\n"
       "Besides each value's own range, the loader checks the values together:\n"
       "FloatVoltage <= AbsorptionVoltage <= BulkVoltage, RebulkVoltage < FloatVoltage,\n"
       "AlternatorHardShutdownV above BulkVoltage (or 0), TargetVoltageSetpoint at most\n"
       "BulkVoltage + 0.3 V, MinDuty <= MaxDuty, alarm low below alarm high,\n"
       "TempWarnExcess < TempCritExcess, load-dump tiers in order, ascending RPM breakpoints.\n\n";
  o << "Contents: ";
  bool first = true;
  for (auto g : kGroups) {
    o << (first ? "" : " · ") << "[" << toString(g) << "](#" << tomlTableName(g) << ")";
    first = false;
  }
  o << " · [Settings](#settings)\n";
  for (auto g : kGroups) {
    o << "\n<a id=\"" << tomlTableName(g) << "\"></a>\n## " << toString(g) << " — `[" << tomlTableName(g)
      << "]`\n\n| Parameter | Default | Unit | Allowed | Description |\n|---|---|---|---|---|\n";
    for (const auto& s : catalogue()) {
      if (s.group != g) continue;
      o << "| `" << s.name << "` | " << paramDefault(s, false) << " | " << mdCell(s.unit) << " | "
        << paramRange(s) << " | " << mdCell(s.help) << " |\n";
    }
    bool header = false;  // settings that share the table ([can])
    for (const auto& s : settingsSchema()) {
      if (s.table != tomlTableName(g)) continue;
      if (!header)
        o << "\nSettings in the same table (read at start only):\n\n"
             "| Key | Default | Allowed | Description |\n|---|---|---|---|\n";
      header = true;
      o << "| `" << s.key << "` | `" << mdCell(settingDefault(s)) << "` | " << mdCell(settingRange(s))
        << " | " << mdCell(s.help) << " |\n";
    }
  }
  o << "\n<a id=\"settings\"></a>\n## Settings\n\n"
       "Non-parameter settings: hardware wiring, real-time, web, store and log. They are read\n"
       "at start only (restart the service after a change).\n";
  for (auto table : settingsTables()) {
    o << "\n### `[" << table << "]`\n\n| Key | Default | Allowed | Description |\n|---|---|---|---|\n";
    for (const auto& s : settingsSchema()) {
      if (s.table != table) continue;
      o << "| `" << s.key << "` | `" << mdCell(settingDefault(s)) << "` | " << mdCell(settingRange(s))
        << " | " << mdCell(s.help) << " |\n";
    }
  }
  return o.str();
}

struct Output {
  const char* path;  // relative to the source root
  std::string (*make)();
};
const Output kOutputs[] = {{"config/xregulator.toml", tomlText}, {"docs/parameters.md", markdownText}};

std::string readFile(const std::string& path, bool& ok) {
  std::ifstream in(path, std::ios::binary);
  ok = static_cast<bool>(in);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int usage() {
  std::cerr << "usage: xr_gendocs toml | markdown | write ROOT | check ROOT\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  const std::string cmd = argv[1];
  if (cmd == "toml" && argc == 2) {
    std::cout << tomlText();
    return 0;
  }
  if (cmd == "markdown" && argc == 2) {
    std::cout << markdownText();
    return 0;
  }
  if ((cmd == "write" || cmd == "check") && argc == 3) {
    const std::string root = argv[2];
    int stale = 0;
    for (const auto& out : kOutputs) {
      const std::string path = root + "/" + out.path;
      const std::string want = out.make();
      bool ok = false;
      const std::string have = readFile(path, ok);
      if (ok && have == want) continue;
      if (cmd == "check") {
        std::cerr << out.path << " is " << (ok ? "stale" : "missing")
                  << ": regenerate it with `cmake --build build --target regen-docs` and commit it\n";
        ++stale;
        continue;
      }
      std::ofstream f(path, std::ios::binary | std::ios::trunc);
      f << want;
      if (!f) {
        std::cerr << "cannot write " << path << "\n";
        return 1;
      }
      std::cout << "wrote " << out.path << "\n";
    }
    return stale ? 1 : 0;
  }
  return usage();
}
