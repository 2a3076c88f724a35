#pragma once
// --sim: the simulated board (SimWorld: plant + chip models on a simulated
// I2C bus, simulated PWM/GPIO/watchdog/1-Wire) with the REAL INA228 and
// ADS1115 drivers on top, the virtual clock (paced with --speed X, unpaced
// with --speed max), the scenario player and the sim_* truth.
#include <filesystem>
#include <memory>
#include <optional>

#include "app/cli.h"
#include "config/settings.h"
#include "drivers/fast_sensors/driver_sensors.h"
#include "drivers/onewire/ds18b20_reader.h"
#include "drivers/sim/runner/sim_ready_edges.h"
#include "drivers/sim/scenario.h"
#include "drivers/sim/sim_clock.h"
#include "drivers/sim/sim_world.h"
#include "runtime/handoffs.h"
#include "runtime/monotonic_clock.h"
#include "runtime/output_mirror.h"

namespace xr::app {

class SimRig final : public rt::TickHook, public rt::TruthSource {
 public:
  // Throws std::runtime_error (with a clear message) on setup errors.
  SimRig(const sim::Scenario& scenario, const Settings& settings, const CliOptions& cli);
  ~SimRig() override;

  // Wire the outputs, mirrored to --sim-outputs when given.
  rt::CycleDevices devices();
  Clock& loopClock() { return paced_ ? static_cast<Clock&>(*paced_) : static_cast<Clock&>(simClock_); }
  // Maps a loop deadline to wall time (empty under --speed max).
  std::function<TimeNs(TimeNs)> wallDeadlineOf();
  rt::MonotonicClock& wall() { return wall_; }
  DriverSensors::StartReport startSensors(double bovlVolts);
  void attach(rt::Handoffs& h) { handoffs_ = &h; }
  rt::OutputMirror* mirror() { return mirror_.get(); }
  sim::SimWorld& world() { return world_; }

  // TickHook: scenario events, the DS18B20 read (1 Hz of virtual time), test faults.
  void beforeTick(TimeNs now) override;
  // TruthSource
  void fill(rt::SimTruth& t) noexcept override;

 private:
  static sim::WorldConfig worldConfig(const sim::Scenario& s, const CliOptions& cli,
                                      const std::filesystem::path& w1);

  const sim::Scenario& scenario_;
  CliOptions cli_;
  std::filesystem::path tmpDir_;
  sim::SimWorld world_;
  sim::SimClock simClock_;
  rt::MonotonicClock wall_;
  std::unique_ptr<rt::PacedClock> paced_;
  DriverSensors sensors_;
  sim::SimReadyEdges readyEdges_;
  std::unique_ptr<Ds18b20Reader> ds18b20_;
  sim::ScenarioPlayer player_;
  std::unique_ptr<rt::OutputMirror> mirror_;
  std::unique_ptr<rt::MirroredPwm> mPwm_;
  std::unique_ptr<rt::MirroredDigitalOutput> mEnable_, mBuzzer_;
  rt::Handoffs* handoffs_ = nullptr;
  TimeNs start_ = -1;
  TimeNs nextTempRead_ = 0;
  bool faultFired_ = false;
};

}  // namespace xr::app
