#pragma once
// Scenario files (docs/simulator.md "Scenario file"): TOML describing the boat, the
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

// What the simulated BMS does on its bus (bms_can = ...): talks, is silent
// (a cut wire), or sends its limits in frames too short to decode.
enum class BmsCanMode { Talking, Silent, ShortFrames };

// [bms] (docs/integrations.md): a simulated LFP BMS on the simulated BMS CAN bus, driven
// by the plant's truth, opening the plant's BMS disconnect when its limits
// are ignored (drivers/sim/bms/sim_bms.h).
struct ScenarioBms {
  static constexpr double kCellCvlV = 3.55;  // an LFP BMS's usual charge voltage per cell
  bool can = false;                          // can = true: the BMS talks on the bus
  std::string protocol = "victron";          // victron | pylontech | rec (what the daemon decodes)
  int cells = 0;                             // cells in series it is set up for; 0 = the [battery]'s
  double cvl_v = 0.0;                        // its charge voltage limit; 0 = cells x kCellCvlV
  double ccl_max_a = 100.0;                  // its CCL before the SoC / cold taper
  double open_after_s = 3.0;                 // limits ignored this long: the contactor opens
  double cell_spread_v = 0.0;                // rec: highest cell this far over the average (0x373)
};

struct ScenarioEvent {
  double at_s = 0.0;
  int line = 0;
  std::optional<double> rpm, house_a, ambient_f, battery_temp_c;
  std::optional<bool> ignition;            // ignition = "on" | "off"
  std::optional<bool> pairing_button;      // pairing_button = "pressed" | "released"
  std::optional<bool> bms_connected;       // bms = "connect" | "disconnect"
  std::optional<bool> bms_charge_enabled;  // bms_input = "charge_enabled" | "charge_disabled"
  std::optional<bool> charger_on;          // charger = "on" | "off" (shore power; needs [charger])
  // The simulated BMS on CAN (docs/integrations.md; only with [bms] can = true):
  std::optional<BmsCanMode> bms_can;  // bms_can = "talking" | "silent" | "short_frames"
  std::optional<double> bms_ccl_a;    // forced CCL (A); < 0 = "auto" (the BMS's own taper)
  std::optional<double> bms_cvl_v;    // forced CVL (V); < 0 = "auto"
  std::optional<bool> bms_warn;       // bms_warn = "high_voltage" | "none"
  std::optional<bool> ecu_talking;    // ecu = "talking" | "silent" (only with [engine] ecu = true)
  bool touchesSimCan() const { return bms_can || bms_ccl_a || bms_cvl_v || bms_warn || ecu_talking; }
  std::optional<Command> command;
  std::vector<ParamOverride> set;
  std::optional<Fault> fault;  // inject (with value where one applies)
  std::optional<Fault> clear;
  double value = 0.0;
};

// [gps]: a simulated GNSS receiver on the simulated NMEA 2000 bus (with
// [can] n2k_interface set) sends the boat's position every second: 129029
// (GNSS Position Data, fast packet) or 129025 (Position, Rapid Update).
struct ScenarioGps {
  bool enabled = false;
  double latitude = 0.0, longitude = 0.0;  // degrees, north and east positive
  std::uint32_t pgn = 129029;
};
// [weather]: the forecast client in --sim ([integrations.weather] with
// enabled = true and these keys; docs/integrations.md "Weather").
struct ScenarioWeather {
  std::string url;
  std::optional<double> latitude, longitude;
  std::optional<int> refresh_min;
};

struct Scenario {
  std::string name;
  std::string source;  // file name used in messages
  double duration_s = 3600.0;
  std::uint64_t seed = 1;
  // set_up = false: the boat as delivered, before its set-up page; the
  // daemon's "not set up" limits apply (docs/simulator.md "Scenario file").
  // A scenario's boat is otherwise set up (config/param_sources.h).
  bool set_up = true;
  std::vector<ParamOverride> config;
  PlantConfig plant;
  NoiseConfig noise;
  ScenarioBms bms;
  // [engine] ecu = true: a simulated engine ECU on the simulated NMEA 2000
  // bus sends 127488 (engine speed, every 0.1 s) from the plant's rpm.
  bool engine_ecu = false;
  ScenarioGps gps;
  std::optional<ScenarioWeather> weather;
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
  // returns the events that carry a command, a parameter set or a change of
  // the simulated BMS, for the caller to apply.
  template <typename OnControl>
  void applyDue(double t, SimWorld& w, OnControl&& onControl) {
    while (next_ < s_.events.size() && s_.events[next_].at_s <= t) {
      const ScenarioEvent& e = s_.events[next_++];
      applyToWorld(e, w);
      if (e.command || !e.set.empty() || e.touchesSimCan()) onControl(e);
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
