#include "params/params.h"

#include <cmath>
#include <limits>

namespace xr {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const ParamSpec kCatalogue[] = {
#define XR_PARAM(name, kind, group, unit, def, lo, hi, help)                                     \
  ParamSpec{#name,                                                                               \
            ParamKind::kind,                                                                     \
            ParamGroup::group,                                                                   \
            unit,                                                                                \
            static_cast<double>(def),                                                            \
            static_cast<double>(lo),                                                             \
            static_cast<double>(hi),                                                             \
            help,                                                                                \
            [](const Params& p, std::size_t) { return static_cast<double>(p.name); },           \
            [](Params& p, std::size_t, double v) { p.name = static_cast<detail::kind##_t>(v); }, \
            RpmTable{}},
#define XR_CHOICE(name, group, def, count, choices, help)                                   \
  ParamSpec{#name,                                                                         \
            ParamKind::Int,                                                                \
            ParamGroup::group,                                                             \
            "",                                                                            \
            static_cast<double>(def),                                                      \
            0.0,                                                                           \
            static_cast<double>((count) - 1),                                              \
            help,                                                                          \
            [](const Params& p, std::size_t) { return static_cast<double>(p.name); },     \
            [](Params& p, std::size_t, double v) { p.name = static_cast<int>(v); },        \
            RpmTable{},                                                                    \
            choices},
#define XR_TABLE(name, group, unit, lo, hi, help, ...)                        \
  ParamSpec{#name,                                                            \
            ParamKind::Table,                                                 \
            ParamGroup::group,                                                \
            unit,                                                             \
            kNaN,                                                             \
            static_cast<double>(lo),                                          \
            static_cast<double>(hi),                                          \
            help,                                                             \
            [](const Params& p, std::size_t i) { return p.name.at(i); },      \
            [](Params& p, std::size_t i, double v) { p.name.at(i) = v; },     \
            RpmTable{__VA_ARGS__}},
#include "params/catalogue.def"
#undef XR_PARAM
#undef XR_CHOICE
#undef XR_TABLE
};

}  // namespace

std::span<const ParamSpec> catalogue() { return kCatalogue; }

const ParamSpec* findParam(std::string_view name) {
  for (const auto& s : kCatalogue)
    if (s.name == name) return &s;
  return nullptr;
}

std::string_view toString(ParamGroup g) {
  switch (g) {
    case ParamGroup::Voltage: return "Voltage";
    case ParamGroup::Overvoltage: return "Overvoltage";
    case ParamGroup::SensorHealth: return "SensorHealth";
    case ParamGroup::Shutdown: return "Shutdown";
    case ParamGroup::Current: return "Current";
    case ParamGroup::Tuning: return "Tuning";
    case ParamGroup::Charging: return "Charging";
    case ParamGroup::Battery: return "Battery";
    case ParamGroup::Temperature: return "Temperature";
    case ParamGroup::Alarms: return "Alarms";
    case ParamGroup::Modes: return "Modes";
    case ParamGroup::Can: return "Can";
    case ParamGroup::RpmTables: return "RpmTables";
  }
  return "?";
}

std::string_view tomlTableName(ParamGroup g) {
  switch (g) {
    case ParamGroup::Voltage: return "voltage";
    case ParamGroup::Overvoltage: return "overvoltage";
    case ParamGroup::SensorHealth: return "sensor_health";
    case ParamGroup::Shutdown: return "shutdown";
    case ParamGroup::Current: return "current";
    case ParamGroup::Tuning: return "tuning";
    case ParamGroup::Charging: return "charging";
    case ParamGroup::Battery: return "battery";
    case ParamGroup::Temperature: return "temperature";
    case ParamGroup::Alarms: return "alarms";
    case ParamGroup::Modes: return "modes";
    case ParamGroup::Can: return "can";
    case ParamGroup::RpmTables: return "rpm_tables";
  }
  return "?";
}

std::string_view toString(ParamKind k) {
  switch (k) {
    case ParamKind::Float: return "float";
    case ParamKind::Int: return "int";
    case ParamKind::Bool: return "bool";
    case ParamKind::Table: return "table";
  }
  return "?";
}

std::string_view choiceName(const ParamSpec& spec, int index) {
  std::string_view rest = spec.choices;
  for (int i = 0; !rest.empty(); ++i) {
    const auto comma = rest.find(',');
    if (i == index) return rest.substr(0, comma);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return {};
}

std::optional<int> choiceIndex(const ParamSpec& spec, std::string_view name) {
  for (int i = 0; !choiceName(spec, i).empty(); ++i)
    if (choiceName(spec, i) == name) return i;
  return std::nullopt;
}

bool valueFits(const ParamSpec& spec, double v) {
  if (!std::isfinite(v)) return false;
  if (v < spec.min || v > spec.max) return false;
  if (spec.kind == ParamKind::Int || spec.kind == ParamKind::Bool) return v == std::floor(v);
  return true;
}

}  // namespace xr
