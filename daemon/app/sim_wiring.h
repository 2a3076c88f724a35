#pragma once
// --sim: the one simulator rig (daemon/sim_rig) plus what only the daemon
// adds around it: pacing against wall time (--speed X; none under --speed
// max), the --sim-outputs mirror of the field outputs, and the hidden test
// faults that prove every exit path leaves the field off.
#include <fstream>
#include <functional>
#include <memory>

#include "app/cli.h"
#include "config/settings.h"
#include "drivers/sim/scenario.h"
#include "runtime/cycle_devices.h"
#include "runtime/handoffs.h"
#include "runtime/monotonic_clock.h"
#include "runtime/output_mirror.h"
#include "sim_rig/sim_rig.h"

namespace xr::app {

// A scenario's [weather] turns the forecast client on in --sim, with its
// url and, when given, its position and refresh (docs/simulator.md).
void applyScenarioWeather(const sim::Scenario& scenario, WeatherSettings& weather);

// A scenario's [config] on top of the file, with the battery profile under
// both, passes the checks on the whole set every other layer passes
// (docs/configuration.md "Checks on the whole set"); else each problem is
// printed and false returned (the daemon exits 64: bad command-line input).
bool scenarioConfigFits(const Params& effective, const std::string& source);

class SimWiring final : public rt::TickHook {
 public:
  // Throws std::runtime_error (with a clear message) on setup errors.
  // `canLog`: --can-log, already open (null = none).
  // `tachPulleyRatio`: the file's, when the set-up page chose another
  // (sim_rig.h SimRigOptions).
  SimWiring(const sim::Scenario& scenario, const Settings& settings, const CliOptions& cli,
            std::unique_ptr<std::ofstream> canLog, std::optional<double> tachPulleyRatio = {});

  // The rig's devices, outputs mirrored to --sim-outputs when given.
  rt::CycleDevices devices();
  Clock& loopClock() { return paced_ ? static_cast<Clock&>(*paced_) : rig_.clock(); }
  // Maps a loop deadline to wall time (empty under --speed max).
  std::function<TimeNs(TimeNs)> wallDeadlineOf();
  rt::MonotonicClock& wall() { return wall_; }
  DriverSensors::StartReport startSensors(double bovlVolts) { return rig_.startSensors(bovlVolts); }
  void attach(rt::Handoffs& h) { rig_.attach(h); }
  std::string w1Root() const { return rig_.w1Root(); }
  rt::OutputMirror* mirror() { return mirror_.get(); }
  // The simulated pairing button, only with [pairing] button_line set (as on the board).
  ButtonInput* pairingButton() { return buttonWired_ ? &rig_.world().pairingButton() : nullptr; }

  // TickHook: the test faults (--test-fault), at their simulated time.
  void beforeTick(TimeNs now) override;

 private:
  CliOptions cli_;
  std::unique_ptr<std::ofstream> canLog_;  // --can-log (before rig_: the rig writes to it)
  sim::SimRig rig_;
  rt::MonotonicClock wall_;
  std::unique_ptr<rt::PacedClock> paced_;
  std::unique_ptr<rt::OutputMirror> mirror_;
  std::unique_ptr<rt::MirroredPwm> mPwm_;
  std::unique_ptr<rt::MirroredDigitalOutput> mEnable_, mBuzzer_;
  bool faultFired_ = false;
  bool buttonWired_ = false;
};

}  // namespace xr::app
