#include "drivers/sim/runner/sim_runner.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <ostream>

#include "control/regulator.h"
#include "drivers/fast_sensors/driver_sensors.h"
#include "drivers/onewire/ds18b20_handoff.h"
#include "drivers/onewire/ds18b20_reader.h"
#include "drivers/sim/runner/scratch_dir.h"
#include "drivers/sim/runner/sim_ready_edges.h"
#include "drivers/sim/sim_clock.h"
#include "params/derived.h"
#include "runtime/control_core.h"
#include "runtime/control_cycle.h"
#include "runtime/control_loop.h"
#include "runtime/loop_stats.h"

namespace xr::sim {
namespace fs = std::filesystem;

namespace {

class RegulatorCore final : public rt::ControlCore {
 public:
  explicit RegulatorCore(const Params& p) : reg_(p) {}
  const Outputs& step(const Inputs& in) override { return reg_.step(in); }
  void setParams(const Params& p) override { reg_.setParams(p); }
  bool command(const Command& c) override { return reg_.command(c); }
  const Outputs& completeTelemetry() override { return reg_.completeTelemetry(); }

 private:
  Regulator reg_;
};

class WorldTruth final : public rt::TruthSource {
 public:
  explicit WorldTruth(SimWorld& w) : w_(w) {}
  void fill(rt::SimTruth& t) noexcept override {
    const SimTruth s = w_.truth();
    t.valid = true;
    t.sim_battery_v = s.plant.battery_v;
    t.sim_alt_a = s.plant.alt_a;
    t.sim_alt_temp_f = s.plant.alt_temp_f;
    t.sim_soc_pct = s.plant.soc_pct;
    t.sim_bms_connected = s.plant.bms_connected;
    t.sim_field_on = s.field_on;
  }

 private:
  SimWorld& w_;
};

// The loop's Clock: before virtual time moves to t, the scenario events due
// at t are applied, the slow 1-Wire reader runs on its virtual 1 s cadence,
// and the rows the cycle queued are drained (everything on one thread, so
// the run is deterministic). `Before` is the caller's lambda, called
// directly (no std::function hop: this runs every tick).
template <typename Before>
class HookedClock final : public Clock {
 public:
  HookedClock(SimClock& inner, Before& before) : inner_(inner), before_(before) {}
  TimeNs now() const noexcept override { return inner_.now(); }
  void sleepUntil(TimeNs t) noexcept override {
    before_(t);
    inner_.sleepUntil(t);
  }

 private:
  SimClock& inner_;
  Before& before_;
};

WorldConfig worldConfigOf(const SimRunOptions& o, const fs::path& w1) {
  WorldConfig c;
  c.plant = o.scenario.plant;
  c.noise = o.scenario.noise;
  c.seed = o.seed.value_or(o.scenario.seed);
  c.w1Root = w1;
  c.maxStep = fromUs(o.settings.runtime.control_period_us);
  return c;
}

}  // namespace

struct SimRunner::Impl {
  SimRunOptions opts;
  fs::path w1Dir;
  Params params;
  SimWorld world;
  SimClock simClock;
  rt::Handoffs handoffs;
  DriverSensors sensors;
  SimReadyEdges readyEdges;
  RegulatorCore core;
  WorldTruth truth;
  rt::LoopStats stats;
  std::unique_ptr<rt::ControlCycle> cycle;
  std::unique_ptr<rt::ControlLoop> loop;
  std::unique_ptr<Ds18b20Reader> w1Reader;
  ScenarioPlayer player;
  std::atomic<bool> stopEarly{false};

  static Params initialParams(const SimRunOptions& o) {
    Params p = o.baseParams.value_or(Params{});
    applyOverrides(p, o.scenario.config, o.scenario.source);
    return p;
  }

  explicit Impl(SimRunOptions o, fs::path w1)
      : opts(std::move(o)),
        w1Dir(std::move(w1)),
        params(initialParams(opts)),
        world(worldConfigOf(opts, w1Dir), opts.settings.hardware),
        simClock(world, opts.speed),
        handoffs(params),
        sensors(world.i2c(), opts.settings.hardware, simClock,
                opts.settings.hardware.ads_alert_rdy_line >= 0),
        readyEdges(world),
        core(params),
        truth(world),
        player(opts.scenario) {}
};

SimRunner::SimRunner(SimRunOptions opts) {
  fs::path w1 = makeScratchDir("xr-sim-w1-");
  d_ = std::make_unique<Impl>(std::move(opts), w1);
}

SimRunner::~SimRunner() {
  if (d_ && !d_->w1Dir.empty()) {
    d_->w1Reader.reset();
    std::error_code ec;
    fs::remove_all(d_->w1Dir, ec);
  }
}

rt::Handoffs& SimRunner::handoffs() noexcept { return d_->handoffs; }
SimWorld& SimRunner::world() noexcept { return d_->world; }

void SimRunner::requestStop() noexcept {
  d_->stopEarly.store(true);
  if (d_->loop) d_->loop->requestStop();
}

SimRunResult SimRunner::run() {
  Impl& d = *d_;
  SimRunResult res;
  const auto wall0 = std::chrono::steady_clock::now();
  // The board is powered before the daemon starts: the INA228/ADS1115 have
  // been converting with their reset configuration for a while (a driver
  // that trusts a result register before the first conversion would read 0
  // on a cold chip; that case has its own test).
  d.world.advanceTo(d.world.now() + fromMs(d.opts.coldStart ? 0 : 100));
  const TimeNs start = d.world.now();

  rt::CycleConfig cc;
  cc.rowPeriod = d.opts.telemetryRateHz > 0 ? fromSec(1.0 / d.opts.telemetryRateHz) : 0;
  cc.blockOnFullRows = false;  // drained every tick below, never full
  if (d.opts.speed <= 0.0) cc.thinForUnpacedRun();
  rt::CycleDevices dev;
  dev.sensors = &d.sensors;
  dev.pwm = &d.world.pwm();
  dev.fieldEnable = &d.world.fieldEnable();
  dev.buzzer = &d.world.buzzer();
  dev.bms = &d.world.bmsLine();
  dev.ignition = &d.world.ignition();
  dev.watchdog = &d.world.watchdog();
  dev.truth = &d.truth;
  if (d.sensors.ads().pacing() == AdsPacing::ReadyEdge) dev.adsReady = &d.readyEdges;
  d.cycle = std::make_unique<rt::ControlCycle>(d.core, dev, d.handoffs, d.stats, d.simClock, cc);

  if (!d.w1Dir.empty()) {
    SimWorld* w = &d.world;
    d.w1Reader = std::make_unique<Ds18b20Reader>(d.w1Dir.string(), d.opts.settings.hardware.onewire_sensor_id,
                                                 fromSec(1.0), [w] { return w->now(); });
  }

  // Pop targets made once: a RuntimeSnapshot is large and drain() runs
  // every tick (rows come at the telemetry rate only).
  rt::RuntimeSnapshot snap;
  Event e;
  auto drain = [&] {
    while (d.handoffs.rows.pop(snap)) {
      SimRow row;
      row.t_s = toSec(snap.telemetry.now - start);
      row.telemetry = snap.telemetry;
      row.sim = snap.sim;
      // Truth at drain time equals truth at the row's tick: rows are drained
      // before virtual time moves on.
      const SimTruth t = d.world.truth();
      row.plant = t.plant;
      row.inaAlert = t.ina_alert;
      if (d.opts.onRow) d.opts.onRow(row);
      if (d.opts.keepRows) res.rows.push_back(std::move(row));
    }
    while (d.handoffs.events.pop(e)) {
      if (d.opts.onEvent) d.opts.onEvent(e);
      res.events.push_back(e);
    }
  };

  TimeNs nextW1 = start;
  auto before = [&](TimeNs t) {
    // Rows come at the telemetry rate and events rarely: the out-of-line
    // drain only when something is queued.
    if (!d.handoffs.rows.empty() || !d.handoffs.events.empty()) drain();
    d.player.applyDue(toSec(t - start), d.world, [&](const ScenarioEvent& e) {
      if (e.command) d.handoffs.submitCommand(*e.command);
      if (!e.set.empty()) {
        applyOverrides(d.params, e.set, d.opts.scenario.source);
        d.handoffs.submitParams(d.params);
      }
    });
    if (d.w1Reader && t >= nextW1) {
      nextW1 += fromSec(1.0);
      d.w1Reader->readOnce();
      d.handoffs.temperature.store(temperatureHandoff(d.w1Reader->latest()));
    }
  };
  HookedClock<decltype(before)> clock(d.simClock, before);

  d.sensors.start(start, voltageHardwareLimit(d.params));
  rt::LoopConfig lc;
  lc.period = fromUs(d.opts.settings.runtime.control_period_us);
  lc.duration = fromSec(d.opts.durationS.value_or(d.opts.scenario.duration_s));
  d.loop = std::make_unique<rt::ControlLoop>(*d.cycle, clock, d.stats, lc);
  if (d.stopEarly.load()) d.loop->requestStop();
  d.loop->run();
  drain();

  res.finalTruth = d.world.truth().plant;
  res.health = d.cycle->health();
  res.loop = d.stats.summary();
  res.ticks = d.cycle->ticks();
  res.i2cTransfers = d.world.bus().transfers();
  res.i2cFailures = d.world.bus().failedTransfers();
  res.inaProtocolErrors = d.world.ina().protocolErrors();
  res.adsProtocolErrors = d.world.ads().protocolErrors();
  res.fieldEnableChanges = d.world.simFieldEnable().log().count();
  res.watchdogKicks = d.world.simWatchdog().kicks();
  res.watchdogLongestGap = d.world.simWatchdog().longestGap();
  res.finalFieldEnable = d.world.simFieldEnable().level();
  res.finalDuty = d.world.simPwm().duty();
  res.simulatedS = toSec(d.world.now() - start);
  res.wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return res;
}

namespace {
void putValue(std::ostream& os, const ColumnValue& v) {
  char buf[48];
  if (const double* x = std::get_if<double>(&v)) {
    // Fixed precision: byte-identical output for identical runs.
    std::snprintf(buf, sizeof buf, "%.4f", *x);
    os << buf;
  } else if (const bool* b = std::get_if<bool>(&v)) {
    os << (*b ? '1' : '0');
  } else {
    os << std::get<std::string_view>(v);
  }
}
}  // namespace

void writeCsvHeader(std::ostream& os) {
  Telemetry t;
  bool first = true;
  visitTelemetryColumns(t, 0, [&](std::string_view name, const ColumnValue&) {
    if (!first) os << ',';
    first = false;
    os << name;
  });
  os << ",sim_battery_v,sim_alt_a,sim_alt_temp_f,sim_soc_pct,sim_bms_connected,sim_field_on\n";
}

void writeCsvRow(std::ostream& os, const SimRow& r) {
  bool first = true;
  Telemetry t = r.telemetry;
  visitTelemetryColumns(t, t.now - fromSec(r.t_s), [&](std::string_view name, const ColumnValue& v) {
    if (!first) os << ',';
    first = false;
    if (name == "t_s")
      putValue(os, ColumnValue{r.t_s});
    else
      putValue(os, v);
  });
  os << ',';
  putValue(os, r.sim.sim_battery_v);
  os << ',';
  putValue(os, r.sim.sim_alt_a);
  os << ',';
  putValue(os, r.sim.sim_alt_temp_f);
  os << ',';
  putValue(os, r.sim.sim_soc_pct);
  os << ',' << (r.sim.sim_bms_connected ? '1' : '0') << ',' << (r.sim.sim_field_on ? '1' : '0') << '\n';
}

}  // namespace xr::sim
