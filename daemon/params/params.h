#pragma once
// Params: one immutable value holding every user-settable parameter, generated
// from catalogue.def. The regulator receives a whole Params between ticks and
// never sees one mutated mid-tick (docs/architecture.md "One idea: a pure core inside a thin shell").
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

namespace xr {

inline constexpr std::size_t RPM_TABLE_SIZE = 10;  // docs/control.md "RPM tables"
using RpmTable = std::array<double, RPM_TABLE_SIZE>;

enum class ParamKind { Float, Int, Bool, Table };

enum class ParamGroup {
  Voltage,
  Overvoltage,
  SensorHealth,
  Shutdown,
  Current,
  Tuning,
  Charging,
  Battery,
  Temperature,
  Alarms,
  Modes,
  Can,  // [can]: following a BMS (the interface settings sit beside these)
  RpmTables,
};

namespace detail {
using Float_t = double;
using Int_t = int;
using Bool_t = bool;
}  // namespace detail

struct Params {
#define XR_PARAM(name, kind, group, unit, def, lo, hi, help) detail::kind##_t name = def;
#define XR_CHOICE(name, group, def, count, choices, help) int name = def;
#define XR_TABLE(name, group, unit, lo, hi, help, ...) RpmTable name{__VA_ARGS__};
#include "params/catalogue.def"
#undef XR_PARAM
#undef XR_CHOICE
#undef XR_TABLE
  // Not a parameter (no catalogue entry: never read from a file, a PATCH or
  // the store): the "not set up" charge ceiling, set only by the running
  // layer (config/setup_pending.h); 0 = set up, no ceiling. The core clamps
  // every voltage target to it, so no value can leak past the lowered set.
  double SetupCeilingV = 0.0;
  // Not a parameter either: not set up and nobody wrote a bank voltage, so
  // the bank class is read from the battery (docs/configuration.md "Not set
  // up"). The core keeps the field off and the voltage trips unarmed until
  // the first battery-voltage reading, then runs withBankClass(p, class of
  // that reading) (params/derived.h).
  bool SetupBankFromBattery = false;
  bool operator==(const Params&) const = default;
};

// One catalogue entry. Values are exchanged as double (ints and bools are
// whole numbers); tables are exchanged element by element.
struct ParamSpec {
  std::string_view name;
  ParamKind kind;
  ParamGroup group;
  std::string_view unit;
  double defaultValue;  // tables: NaN (see tableDefault)
  double min;
  double max;
  std::string_view help;
  // Scalars: index ignored. Tables: index 0..RPM_TABLE_SIZE-1.
  double (*get)(const Params&, std::size_t index);
  void (*set)(Params&, std::size_t index, double value);
  RpmTable tableDefault;
  // XR_CHOICE parameters (kind Int, values 0..n-1): the names of the values,
  // comma-separated ("lifepo4,agm,..."); empty for every other parameter.
  std::string_view choices = {};
};

std::span<const ParamSpec> catalogue();
const ParamSpec* findParam(std::string_view name);
std::string_view toString(ParamGroup g);       // "Voltage"
std::string_view tomlTableName(ParamGroup g);  // "voltage"
std::string_view toString(ParamKind k);

// The name of choice `index` of spec ("agm"), empty when spec has no choices
// or index is out of range; and the index of a name (nullopt when unknown).
std::string_view choiceName(const ParamSpec& spec, int index);
std::optional<int> choiceIndex(const ParamSpec& spec, std::string_view name);

// True when v is acceptable for spec: finite, within [min, max], whole for
// Int/Bool (Bool: 0 or 1).
bool valueFits(const ParamSpec& spec, double v);

}  // namespace xr
