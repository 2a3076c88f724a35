#pragma once
// SimRunner: a whole closed loop in one process, headless. The real drivers
// (INA228, ADS1115 on the simulated I2C bus; DS18B20 reader on the simulated
// w1 tree) feed the real runtime ControlCycle/ControlLoop and the real
// Regulator; the SimWorld plays the plant and the chips; the scenario's
// events are applied between ticks. At speed 0 ("max") virtual time runs as
// fast as the CPU allows and the run is deterministic for a given seed.
//
//   SimRunner r(opts);  SimRunResult res = r.run();
//   res.rows: telemetry rows at telemetryRateHz with the plant's truth.
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/settings.h"
#include "control/telemetry.h"
#include "core/events.h"
#include "drivers/sim/scenario.h"
#include "drivers/sim/sim_world.h"
#include "params/params.h"
#include "runtime/handoffs.h"

namespace xr::sim {

struct SimRunOptions {
  Scenario scenario = defaultScenario();
  Settings settings;                  // hardware (addresses, shunt, front end), control period
  std::optional<Params> baseParams;   // before the scenario's [config]; default = catalogue defaults
  double telemetryRateHz = 10.0;      // rows per simulated second (0 = none)
  std::optional<double> durationS;    // overrides the scenario's duration_s
  std::optional<std::uint64_t> seed;  // overrides the scenario's seed
  double speed = 0.0;                 // 0 = max (no pacing), 1 = real time
  bool keepRows = true;               // collect rows in the result
  bool coldStart = false;             // start the loop the instant the chips power up
  std::function<void(const struct SimRow&)> onRow;  // streaming (CSV writer)
  std::function<void(const Event&)> onEvent;        // events, in order
  std::ostream* canLog = nullptr;                   // every CAN frame, candump format
};

// One telemetry row: what the daemon publishes plus the plant's truth.
struct SimRow {
  double t_s = 0.0;
  Telemetry telemetry;
  rt::SimTruth sim;
  PlantTruth plant;
  bool inaAlert = false;
};

struct SimRunResult {
  std::vector<SimRow> rows;
  std::vector<Event> events;
  std::vector<std::string> canReports;  // what the CAN service reported (bus down, bad frames)
  PlantTruth finalTruth;
  rt::RuntimeHealth health;
  rt::LoopStatsSummary loop;  // the control loop's statistics at the end (rates on virtual time)
  std::uint64_t ticks = 0;
  std::uint64_t i2cTransfers = 0, i2cFailures = 0;
  std::uint64_t inaProtocolErrors = 0, adsProtocolErrors = 0;  // driver bugs the models refused
  std::uint64_t fieldEnableChanges = 0, watchdogKicks = 0;
  TimeNs watchdogLongestGap = 0;
  bool finalFieldEnable = true;
  double finalDuty = 100.0;
  double simulatedS = 0.0, wallS = 0.0;
};

class SimRunner {
 public:
  explicit SimRunner(SimRunOptions opts);
  ~SimRunner();
  SimRunner(const SimRunner&) = delete;
  SimRunner& operator=(const SimRunner&) = delete;

  // Runs the scenario to its end (or until requestStop()); the field is safe
  // (enable LOW, duty 0) when it returns. Call once.
  SimRunResult run();
  // Async-signal-safe stop (starts the controlled ramp).
  void requestStop() noexcept;

  // For a daemon wrapping the run (HTTP, store): the lock-free hand-offs.
  rt::Handoffs& handoffs() noexcept;
  SimWorld& world() noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
};

// CSV per docs/operations.md "Telemetry CSV columns": the telemetry columns, then the sim_* truth columns.
void writeCsvHeader(std::ostream& os);
void writeCsvRow(std::ostream& os, const SimRow& row);

}  // namespace xr::sim
