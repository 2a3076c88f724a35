#include "sim_rig/sim_runner.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/battery_profiles.h"
#include "config/config.h"
#include "control/regulator.h"
#include "params/derived.h"
#include "runtime/control_cycle.h"
#include "runtime/control_loop.h"
#include "runtime/loop_stats.h"
#include "runtime/regulator_core.h"
#include "sim_rig/sim_rig.h"

namespace xr::sim {

struct SimRunner::Impl {
  SimRunOptions opts;
  SimRig rig;
  Regulator regulator;
  rt::RegulatorCore core;
  rt::Handoffs handoffs;
  rt::LoopStats stats;
  std::unique_ptr<rt::ControlCycle> cycle;
  std::unique_ptr<rt::ControlLoop> loop;
  std::vector<std::string> scenarioProblems;
  std::vector<std::string> canReports;
  std::atomic<bool> stopEarly{false};

  static SimRigOptions rigOptions(const SimRunOptions& o) {
    SimRigOptions r;
    r.seed = o.seed;
    r.speed = o.speed;
    r.canLog = o.canLog;
    if (o.coldStart) r.poweredBefore = 0;
    return r;
  }
  static Params initialParams(const SimRunOptions& o) {
    Params p = o.baseParams.value_or(Params{});
    // The battery profile fills what neither the base set (its values that
    // differ from the defaults) nor the scenario's [config] set (docs/batteries.md).
    NameSet pinned = namesDifferingFromDefaults(p);
    applyOverrides(p, o.scenario.config, o.scenario.source);
    for (const auto& c : o.scenario.config) pinned.insert(c.name);
    Params out = applyBatteryProfile(p, pinned).params;
    // The checks on the whole set, as for every layer (docs/configuration.md).
    if (const auto errs = checkConsistency(out, o.scenario.source); !errs.empty())
      throw ScenarioError(errs.front().toString());
    return out;
  }

  explicit Impl(SimRunOptions o)
      : opts(std::move(o)),
        rig(opts.scenario, opts.settings, rigOptions(opts)),
        regulator(initialParams(opts)),
        core(regulator),
        handoffs(initialParams(opts)) {
    rig.attach(handoffs);
    rig.onCanReport([this](const std::string& what) { canReports.push_back(what); });
    rig.onScenarioProblem([this](int line, const std::string& what) {
      scenarioProblems.push_back(opts.scenario.source + ":" + std::to_string(line) + ": " + what);
    });
  }
};

SimRunner::SimRunner(SimRunOptions opts) : d_(std::make_unique<Impl>(std::move(opts))) {}

SimRunner::~SimRunner() = default;

rt::Handoffs& SimRunner::handoffs() noexcept { return d_->handoffs; }
SimWorld& SimRunner::world() noexcept { return d_->rig.world(); }

void SimRunner::requestStop() noexcept {
  d_->stopEarly.store(true);
  if (d_->loop) d_->loop->requestStop();
}

SimRunResult SimRunner::run() {
  Impl& d = *d_;
  SimWorld& world = d.rig.world();
  SimRunResult res;
  const auto wall0 = std::chrono::steady_clock::now();
  const TimeNs start = d.rig.start();

  rt::CycleConfig cc;
  cc.rowPeriod = d.opts.telemetryRateHz > 0 ? fromSec(1.0 / d.opts.telemetryRateHz) : 0;
  cc.blockOnFullRows = false;  // drained at every deadline below, never full
  if (d.opts.speed <= 0.0) cc.thinForUnpacedRun();
  cc.rpmFromN2k = d.opts.settings.can.RpmSource == "n2k";
  d.cycle =
      std::make_unique<rt::ControlCycle>(d.core, d.rig.devices(), d.handoffs, d.stats, d.rig.clock(), cc);

  // Pop targets made once: a RuntimeSnapshot is large.
  rt::RuntimeSnapshot snap;
  Event e;
  auto drain = [&] {
    while (d.handoffs.rows.pop(snap)) {
      SimRow row;
      row.t_s = toSec(snap.telemetry.now - start);
      row.telemetry = snap.telemetry;
      row.sim = snap.sim;
      // Truth at drain time equals truth at the row's tick: the rig drains
      // before virtual time moves on.
      const SimTruth t = world.truth();
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
  d.rig.beforeAdvance(drain);

  d.rig.startSensors(voltageHardwareLimit(d.handoffs.acceptedParams()));
  rt::LoopConfig lc;
  lc.period = fromUs(d.opts.settings.runtime.control_period_us);
  lc.duration = fromSec(d.opts.durationS.value_or(d.opts.scenario.duration_s));
  d.loop = std::make_unique<rt::ControlLoop>(*d.cycle, d.rig.clock(), d.stats, lc);
  if (d.stopEarly.load()) d.loop->requestStop();
  d.loop->run();
  drain();
  d.rig.beforeAdvance({});
  if (!d.scenarioProblems.empty()) throw std::runtime_error(d.scenarioProblems.front());

  res.finalTruth = world.truth().plant;
  res.health = d.cycle->health();
  res.canReports = d.canReports;
  res.loop = d.stats.summary();
  res.ticks = d.cycle->ticks();
  res.i2cTransfers = world.bus().transfers();
  res.i2cFailures = world.bus().failedTransfers();
  res.inaProtocolErrors = world.ina().protocolErrors();
  res.adsProtocolErrors = world.ads().protocolErrors();
  res.fieldEnableChanges = world.simFieldEnable().log().count();
  res.watchdogKicks = world.simWatchdog().kicks();
  res.watchdogLongestGap = world.simWatchdog().longestGap();
  res.finalFieldEnable = world.simFieldEnable().level();
  res.finalDuty = world.simPwm().duty();
  res.simulatedS = toSec(world.now() - start);
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
