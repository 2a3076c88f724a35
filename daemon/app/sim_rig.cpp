#include "app/sim_rig.h"

#include <spdlog/spdlog.h>
#include <stdlib.h>

#include <csignal>
#include <exception>
#include <stdexcept>

#include "drivers/onewire/ds18b20_handoff.h"
#include "drivers/sim/runner/scratch_dir.h"

namespace xr::app {

namespace {
std::filesystem::path makeTempDir() {
  auto dir = sim::makeScratchDir("xregulatord-sim-");
  if (dir.empty())
    throw std::runtime_error("cannot create a temporary directory for the simulated 1-Wire tree");
  return dir;
}
}  // namespace

sim::WorldConfig SimRig::worldConfig(const sim::Scenario& s, const CliOptions& cli,
                                     const std::filesystem::path& w1) {
  sim::WorldConfig c;
  c.plant = s.plant;
  c.noise = s.noise;
  c.seed = cli.seed ? *cli.seed : s.seed;
  c.w1Root = w1 / "w1";
  return c;
}

SimRig::SimRig(const sim::Scenario& scenario, const Settings& settings, const CliOptions& cli)
    : scenario_(scenario),
      cli_(cli),
      tmpDir_(makeTempDir()),
      world_(worldConfig(scenario, cli, tmpDir_), settings.hardware),
      simClock_(world_, 0.0),  // pacing is ours (PacedClock) so period error is measured
      // The simulated board has ALERT/RDY wired: ready-edge pacing when the
      // configuration names a line, as on the board.
      sensors_(world_.i2c(), settings.hardware, simClock_, settings.hardware.ads_alert_rdy_line >= 0),
      readyEdges_(world_),
      player_(scenario) {
  if (cli.speed > 0.0) paced_ = std::make_unique<rt::PacedClock>(simClock_, wall_, cli.speed);
  ds18b20_ = std::make_unique<Ds18b20Reader>((tmpDir_ / "w1").string(), settings.hardware.onewire_sensor_id,
                                             fromSec(1.0), [this] { return world_.now(); });
  if (cli.simOutputs) {
    mirror_ = std::make_unique<rt::OutputMirror>(*cli.simOutputs);
    mPwm_ = std::make_unique<rt::MirroredPwm>(world_.pwm(), *mirror_);
    mEnable_ = std::make_unique<rt::MirroredDigitalOutput>(world_.fieldEnable(), *mirror_,
                                                           rt::MirroredDigitalOutput::Role::FieldEnable);
    mBuzzer_ = std::make_unique<rt::MirroredDigitalOutput>(world_.buzzer(), *mirror_,
                                                           rt::MirroredDigitalOutput::Role::Buzzer);
  }
}

SimRig::~SimRig() {
  std::error_code ec;
  std::filesystem::remove_all(tmpDir_, ec);
}

rt::CycleDevices SimRig::devices() {
  rt::CycleDevices d;
  d.sensors = &sensors_;
  d.pwm = mPwm_ ? static_cast<PwmOutput*>(mPwm_.get()) : &world_.pwm();
  d.fieldEnable = mEnable_ ? static_cast<DigitalOutput*>(mEnable_.get()) : &world_.fieldEnable();
  d.buzzer = mBuzzer_ ? static_cast<DigitalOutput*>(mBuzzer_.get()) : &world_.buzzer();
  d.bms = &world_.bmsLine();
  d.ignition = &world_.ignition();
  d.watchdog = &world_.watchdog();
  d.truth = this;
  d.hook = this;
  d.adsReady = sensors_.ads().pacing() == AdsPacing::ReadyEdge ? &readyEdges_ : nullptr;
  return d;
}

std::function<TimeNs(TimeNs)> SimRig::wallDeadlineOf() {
  if (!paced_) return {};
  rt::PacedClock* p = paced_.get();
  return [p](TimeNs t) { return p->wallDeadline(t); };
}

DriverSensors::StartReport SimRig::startSensors(double bovlVolts) {
  world_.pwm().setEnabled(true);  // the PWM channel runs; GPIO4 gates the field
  return sensors_.start(world_.now(), bovlVolts);
}

void SimRig::beforeTick(TimeNs now) {
  if (start_ < 0) {
    start_ = now;
    nextTempRead_ = now;
  }
  const double t = toSec(now - start_);
  player_.applyDue(t, world_, [this](const sim::ScenarioEvent& e) {
    if (!handoffs_) return;
    if (e.command && !handoffs_->submitCommand(*e.command))
      spdlog::warn("scenario line {}: command queue full, command dropped", e.line);
    if (!e.set.empty()) {
      Params p = handoffs_->acceptedParams();
      try {
        sim::applyOverrides(p, e.set, scenario_.source);
        handoffs_->submitParams(p);
      } catch (const std::exception& ex) {
        spdlog::error("scenario line {}: {}", e.line, ex.what());
      }
    }
  });
  // The 1-Wire thread's job, on virtual time (a wall-clock thread would look
  // stale at --speed max).
  if (now >= nextTempRead_ && handoffs_) {
    ds18b20_->readOnce();
    handoffs_->temperature.store(temperatureHandoff(ds18b20_->latest()));
    nextTempRead_ = now + fromSec(1.0);
  }
  if (cli_.testFault != TestFault::None && !faultFired_ && t >= cli_.testFaultAtS) {
    switch (cli_.testFault) {
      case TestFault::Segv:
        faultFired_ = true;
        std::raise(SIGSEGV);
        break;
      case TestFault::Abort:
        faultFired_ = true;
        std::abort();
      case TestFault::Terminate:
        faultFired_ = true;
        std::terminate();
      case TestFault::ThrowInControl:
        faultFired_ = true;
        throw std::runtime_error("test fault: exception in the control thread");
      default:
        break;  // Throw is raised on the main thread
    }
  }
}

void SimRig::fill(rt::SimTruth& t) noexcept {
  const sim::SimTruth s = world_.truth();
  t.valid = true;
  t.sim_battery_v = s.plant.battery_v;
  t.sim_alt_a = s.plant.alt_a;
  t.sim_alt_temp_f = s.plant.alt_temp_f;
  t.sim_soc_pct = s.plant.soc_pct;
  t.sim_bms_connected = s.plant.bms_connected;
  t.sim_field_on = s.field_on;
}

}  // namespace xr::app
