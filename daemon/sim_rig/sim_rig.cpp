#include "sim_rig/sim_rig.h"

#include <cstdio>
#include <exception>
#include <stdexcept>
#include <system_error>

#include "params/params.h"
#include "runtime/ds18b20_handoff.h"
#include "sim_rig/scratch_dir.h"

namespace xr::sim {

namespace {

std::filesystem::path makeW1Dir() {
  auto dir = makeScratchDir("xr-sim-w1-");
  if (dir.empty())
    throw std::runtime_error("cannot create a temporary directory for the simulated 1-Wire tree");
  return dir;
}

// The battery DS18B20 of the simulated board (docs/batteries.md): the configured id,
// else a fixed one when the scenario puts a sensor on the bank ([battery]
// temp_sensor = true). It sorts after the alternator's simulated sensor.
std::string batteryW1IdOf(const Scenario& s, const Settings& settings) {
  if (!settings.hardware.battery_temp_sensor.empty()) return settings.hardware.battery_temp_sensor;
  return s.plant.battery.temp_sensor ? std::string(kSimBatteryW1Id) : std::string();
}

// The board's analog front end as wired: the tach as calibrated (SimRigOptions).
HardwareSettings tachWiring(HardwareSettings h, const SimRigOptions& o) {
  if (o.tachPulleyRatio) h.frontend.pulley_ratio = *o.tachPulleyRatio;
  return h;
}

WorldConfig worldConfigOf(const Scenario& s, const Settings& settings, const SimRigOptions& o,
                          const std::filesystem::path& w1) {
  WorldConfig c;
  c.plant = s.plant;
  c.noise = s.noise;
  c.seed = o.seed.value_or(s.seed);
  c.w1Root = w1;
  c.batteryW1Id = batteryW1IdOf(s, settings);
  c.maxStep = fromUs(settings.runtime.control_period_us);
  return c;
}

}  // namespace

SimRig::SimRig(Scenario scenario, const Settings& settings, SimRigOptions options)
    : scenario_(std::move(scenario)),
      scratch_(makeW1Dir()),
      world_(worldConfigOf(scenario_, settings, options, scratch_), tachWiring(settings.hardware, options)),
      simClock_(world_, options.speed),
      clock_(*this),
      // The simulated board has ALERT/RDY wired: ready-edge pacing when the
      // configuration names a line, as on the board.
      sensors_(world_.i2c(), settings.hardware, simClock_, settings.hardware.ads_alert_rdy_line >= 0),
      readyEdges_(world_),
      player_(scenario_),
      canLog_(options.canLog),
      canSettings_(settings.can) {
  world_.advanceTo(world_.now() + options.poweredBefore);
  start_ = world_.now();
  nextTempRead_ = start_;
  ds18b20_ = std::make_unique<Ds18b20Reader>(scratch_.string(), settings.hardware.onewire_sensor_id,
                                             fromSec(1.0), [this] { return world_.now(); });
  const std::string batteryId = options.batteryProbeAsConfigured ? settings.hardware.battery_temp_sensor
                                                                 : batteryW1IdOf(scenario_, settings);
  ds18b20_->excludeId(batteryId);
  if (!batteryId.empty())
    batteryDs18b20_ = std::make_unique<Ds18b20Reader>(scratch_.string(), batteryId, fromSec(1.0),
                                                      [this] { return world_.now(); });
}

SimRig::~SimRig() {
  batteryDs18b20_.reset();
  ds18b20_.reset();
  std::error_code ec;
  std::filesystem::remove_all(scratch_, ec);
}

void SimRig::attach(rt::Handoffs& h) {
  handoffs_ = &h;
  can_ = std::make_unique<SimCanRig>(
      scenario_, canSettings_, h, start_, canLog_,
      [this](const std::string& what) {
        if (canReport_)
          canReport_(what);
        else
          std::fprintf(stderr, "%s\n", what.c_str());
      },
      !batteryDs18b20_);
}

rt::CycleDevices SimRig::devices() noexcept {
  rt::CycleDevices d;
  d.sensors = &sensors_;
  d.pwm = &world_.pwm();
  d.fieldEnable = &world_.fieldEnable();
  d.buzzer = &world_.buzzer();
  d.bms = &world_.bmsLine();
  d.ignition = &world_.ignition();
  d.watchdog = &world_.watchdog();
  d.truth = this;
  if (sensors_.ads().pacing() == AdsPacing::ReadyEdge) d.adsReady = &readyEdges_;
  return d;
}

DriverSensors::StartReport SimRig::startSensors(double bovlVolts) {
  world_.pwm().setEnabled(true);  // the PWM channel runs; GPIO4 gates the field
  return sensors_.start(world_.now(), bovlVolts);
}

void SimRig::RigClock::sleepUntil(TimeNs t) noexcept {
  if (rig_.beforeAdvance_) rig_.beforeAdvance_();
  rig_.playDue(t);
  rig_.simClock_.sleepUntil(t);
}

void SimRig::playDue(TimeNs t) {
  player_.applyDue(toSec(t - start_), world_, [this](const ScenarioEvent& e) { applyControl(e); });
  if (can_) can_->step(world_.now(), world_.plant());
  if (handoffs_ && t >= nextTempRead_) {
    nextTempRead_ += fromSec(1.0);
    ds18b20_->readOnce();
    handoffs_->temperature.store(temperatureHandoff(ds18b20_->latest()));
    if (batteryDs18b20_) {
      batteryDs18b20_->readOnce();
      handoffs_->batteryTemp.store(batteryTempHandoff(batteryDs18b20_->latest()));
    }
  }
}

void SimRig::applyControl(const ScenarioEvent& e) {
  auto problem = [&](const std::string& what) {
    if (problem_)
      problem_(e.line, what);
    else
      std::fprintf(stderr, "scenario line %d: %s\n", e.line, what.c_str());
  };
  if (can_ && e.touchesSimCan()) can_->apply(e);
  if (!handoffs_) return;
  if (e.command && !handoffs_->submitCommand(*e.command)) problem("command queue full, command dropped");
  if (!e.set.empty()) {
    // On top of what the loop was last given (the operator's API changes too).
    Params p = handoffs_->acceptedParams();
    try {
      applyOverrides(p, e.set, scenario_.source);
      handoffs_->submitParams(p);
    } catch (const std::exception& ex) {
      problem(ex.what());
    }
  }
}

void SimRig::fill(rt::SimTruth& t) noexcept {
  const SimTruth s = world_.truth();
  t.valid = true;
  t.sim_battery_v = s.plant.battery_v;
  t.sim_alt_a = s.plant.alt_a;
  t.sim_alt_temp_f = s.plant.alt_temp_f;
  t.sim_soc_pct = s.plant.soc_pct;
  t.sim_bms_connected = s.plant.bms_connected;
  t.sim_field_on = s.field_on;
}

}  // namespace xr::sim
