#pragma once
// Scenario files (DESIGN.md "Scenario file"): TOML describing the boat, the
// starting state, parameter overrides and timed events. A bad file (syntax,
// unknown key, unknown fault, value out of range, events out of order) throws
// ScenarioError whose message starts with "file:line:"; the daemon prints it
// and exits non-zero.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/commands.h"
#include "drivers/sim/faults.h"
#include "drivers/sim/sim_world.h"
#include "params/params.h"

namespace xr::sim {

class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One parameter override: scalars have one value, RPM tables RPM_TABLE_SIZE.
struct ParamOverride {
  std::string name;
  std::vector<double> values;
  int line = 0;
};

struct ScenarioEvent {
  double at_s = 0.0;
  int line = 0;
  std::optional<double> rpm, house_a, ambient_f, battery_temp_c;
  std::optional<bool> ignition;            // ignition = "on" | "off"
  std::optional<bool> bms_connected;       // bms = "connect" | "disconnect"
  std::optional<bool> bms_charge_enabled;  // bms_input = "charge_enabled" | "charge_disabled"
  std::optional<Command> command;
  std::vector<ParamOverride> set;
  std::optional<Fault> fault;  // inject (with value where one applies)
  std::optional<Fault> clear;
  double value = 0.0;
};

struct Scenario {
  std::string name;
  std::string source;  // file name used in messages
  double duration_s = 3600.0;
  std::uint64_t seed = 1;
  std::vector<ParamOverride> config;
  PlantConfig plant;
  NoiseConfig noise;
  std::vector<ScenarioEvent> events;  // sorted by at_s (the file must be)
};

Scenario loadScenario(const std::filesystem::path& file);
Scenario parseScenario(std::string_view text, std::string_view sourceName);
// The built-in scenario used when --sim runs without --scenario.
Scenario defaultScenario();

// Apply validated overrides to a parameter set (throws ScenarioError on a
// name or value the catalogue rejects).
void applyOverrides(Params& p, const std::vector<ParamOverride>& o, std::string_view source = "");

// Plays events into a world as time passes. Commands and parameter sets are
// handed to the caller (they go to the regulator between ticks).
class ScenarioPlayer {
 public:
  explicit ScenarioPlayer(const Scenario& s) : s_(s) {}
  // Apply every event with at_s <= t (seconds since start) to the world;
  // returns the events that carry a command or a parameter set, for the
  // caller to apply.
  template <typename OnControl>
  void applyDue(double t, SimWorld& w, OnControl&& onControl) {
    while (next_ < s_.events.size() && s_.events[next_].at_s <= t) {
      const ScenarioEvent& e = s_.events[next_++];
      applyToWorld(e, w);
      if (e.command || !e.set.empty()) onControl(e);
    }
  }
  static void applyToWorld(const ScenarioEvent& e, SimWorld& w);
  bool done() const noexcept { return next_ >= s_.events.size(); }
  std::size_t applied() const noexcept { return next_; }

 private:
  const Scenario& s_;
  std::size_t next_ = 0;
};

}  // namespace xr::sim
