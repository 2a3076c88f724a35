#pragma once
// SimRig: the one simulator rig, used by `xregulatord --sim`, the headless
// SimRunner (tests, benchmarks) and the tests that build a loop of their own.
//
// It is the simulated board under the real drivers: the SimWorld (plant and
// chip models on a simulated I2C bus, simulated PWM, GPIO, watchdog and w1
// sysfs tree), the REAL INA228/ADS1115 drivers (DriverSensors) and DS18B20
// reader on top, the ADS1115 ALERT/RDY edges, the sim_* truth, and the
// scenario player. Its clock() is the control loop's clock: before virtual
// time moves to the next deadline it plays the scenario events due by then
// and the DS18B20 read on its 1 s cadence of virtual time (a wall-clock
// thread would look stale at --speed max), all on the loop's thread, so a
// run is deterministic for a given seed.
//
// Sits above the runtime and the drivers (docs/architecture.md), below the
// daemon's wiring (daemon/app) and the headless runner.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "config/settings.h"
#include "drivers/onewire/ds18b20_reader.h"
#include "drivers/sim/scenario.h"
#include "drivers/sim/sim_clock.h"
#include "drivers/sim/sim_world.h"
#include "runtime/cycle_devices.h"
#include "runtime/driver_sensors.h"
#include "runtime/handoffs.h"
#include "sim_rig/sim_can_rig.h"
#include "sim_rig/sim_ready_edges.h"

namespace xr::sim {

struct SimRigOptions {
  std::optional<std::uint64_t> seed;  // overrides the scenario's seed
  double speed = 0.0;                 // SimClock pacing: 0 = max (none), 1 = real time
  // How long the board has been powered when the loop starts: the INA228 and
  // ADS1115 have been converting with their reset configuration meanwhile (a
  // driver that trusts a result register before the first conversion would
  // read 0 on a cold chip; that case has its own test, with 0 here).
  TimeNs poweredBefore = fromMs(100);
  // --can-log: every CAN frame of the run, candump format (may be null).
  std::ostream* canLog = nullptr;
  // The pulley ratio the simulated board's tach was calibrated with (the
  // file's): the world makes the tach voltage from the engine speed with it,
  // so a different ratio chosen on the set-up page reads as a real board
  // would. Unset: the settings' own (the reading matches the engine).
  std::optional<double> tachPulleyRatio;
  // true (the daemon): the battery probe is read only when the settings name
  // it, as on a board, so "none" chosen on the set-up page is none; the
  // daemon names the scenario's probe in the settings it starts from.
  // false: a scenario's probe is read without being named.
  bool batteryProbeAsConfigured = false;
};

class SimRig final : public rt::TruthSource {
 public:
  // Throws std::runtime_error (with a clear message) when the scratch
  // directory for the simulated 1-Wire tree cannot be made.
  SimRig(Scenario scenario, const Settings& settings, SimRigOptions options = {});
  ~SimRig() override;
  SimRig(const SimRig&) = delete;
  SimRig& operator=(const SimRig&) = delete;

  // Where scenario commands and parameter sets go. Call before the loop runs.
  // The CAN side (sim_can_rig.h) starts here: it posts into `h`.
  void attach(rt::Handoffs& h);
  // A scenario [[events]] set that cannot be applied, or a command the full
  // queue dropped. The loop goes on (the clock cannot throw); without a
  // handler the problem is printed on stderr.
  void onScenarioProblem(std::function<void(int line, const std::string& what)> f) {
    problem_ = std::move(f);
  }
  // Called first at every deadline, before anything moves: what the caller
  // must see at the virtual time of the tick just done (the runner drains
  // its rows here, with the plant's truth of that tick).
  void beforeAdvance(std::function<void()> f) { beforeAdvance_ = std::move(f); }
  // What the CAN service reports (a bus down, bad frames, rate-limited).
  // Without a handler it is printed on stderr.
  void onCanReport(std::function<void(const std::string&)> f) { canReport_ = std::move(f); }
  // The simulated board's 1-Wire sysfs tree (w1_root on a board).
  std::string w1Root() const { return scratch_.string(); }
  // The CAN side; null before attach().
  const SimCanRig* can() const noexcept { return can_.get(); }

  // The seams of one control cycle: the sensors, the world's outputs and
  // inputs, the truth, and the ALERT/RDY edges when the drivers pace on them.
  rt::CycleDevices devices() noexcept;
  // The loop's clock (virtual time; see the top of this file).
  Clock& clock() noexcept { return clock_; }
  // Not RT: the PWM channel runs (GPIO4 gates the field) and both chips are
  // detected and configured.
  DriverSensors::StartReport startSensors(double bovlVolts);

  // Virtual time of the loop's start (scenario times count from it).
  TimeNs start() const noexcept { return start_; }
  SimWorld& world() noexcept { return world_; }
  DriverSensors& sensors() noexcept { return sensors_; }
  const Scenario& scenario() const noexcept { return scenario_; }

  // TruthSource: the plant's truth for the sim_* columns.
  void fill(rt::SimTruth& t) noexcept override;

 private:
  // The loop's Clock: plays what is due, then lets SimClock advance the world.
  class RigClock final : public Clock {
   public:
    explicit RigClock(SimRig& rig) noexcept : rig_(rig) {}
    TimeNs now() const noexcept override { return rig_.simClock_.now(); }
    void sleepUntil(TimeNs t) noexcept override;

   private:
    SimRig& rig_;
  };
  void playDue(TimeNs t);
  void applyControl(const ScenarioEvent& e);

  Scenario scenario_;
  std::filesystem::path scratch_;
  SimWorld world_;
  SimClock simClock_;
  RigClock clock_;
  DriverSensors sensors_;
  SimReadyEdges readyEdges_;
  std::unique_ptr<Ds18b20Reader> ds18b20_;
  std::unique_ptr<Ds18b20Reader> batteryDs18b20_;  // [hardware] battery_temp_sensor (docs/batteries.md)
  ScenarioPlayer player_;
  rt::Handoffs* handoffs_ = nullptr;
  std::function<void(int, const std::string&)> problem_;
  std::function<void()> beforeAdvance_;
  std::function<void(const std::string&)> canReport_;
  std::ostream* canLog_ = nullptr;
  CanSettings canSettings_;
  std::unique_ptr<SimCanRig> can_;
  TimeNs start_ = 0;
  TimeNs nextTempRead_ = 0;
};

// The simulated battery DS18B20's w1 id when the scenario asks for one.
inline constexpr const char* kSimBatteryW1Id = "28-00000b0a77e1";

}  // namespace xr::sim
