#include "app/daemon.h"

#include <spdlog/spdlog.h>
#include <systemd/sd-daemon.h>

#include <cstdio>
#include <exception>
#include <fstream>
#include <memory>

#include "app/can_wiring.h"
#include "app/control_thread.h"
#include "app/csv_writer.h"
#include "app/daemon_notices.h"
#include "app/daemon_rig.h"
#include "app/daemon_services.h"
#include "app/daemon_start.h"
#include "app/supervisor.h"
#include "config/config.h"
#include "control/regulator.h"
#include "params/derived.h"
#include "runtime/control_cycle.h"
#include "runtime/control_loop.h"
#include "runtime/fatal_guard.h"
#include "runtime/regulator_core.h"
#include "runtime/rt_setup.h"

namespace xr::app {

namespace {

// --telemetry-csv and --can-log, opened before any device: a file that cannot
// be created stops the daemon at start with nothing to undo (exit 78).
struct OutputFiles {
  std::unique_ptr<CsvWriter> csv;
  std::unique_ptr<std::ofstream> canLog;
};

bool openOutputFiles(const CliOptions& cli, rt::Handoffs& handoffs, OutputFiles& out) {
  try {
    if (cli.canLog) out.canLog = openCanLog(*cli.canLog);
    if (cli.telemetryCsv) out.csv = std::make_unique<CsvWriter>(*cli.telemetryCsv, handoffs, cli.sim);
    return true;
  } catch (const std::exception& e) {
    spdlog::critical("{}", e.what());
    std::fprintf(stderr, "xregulatord: %s\n", e.what());
    return false;
  }
}

// An unpaced simulation (--speed max) has no deadlines: no real time, no
// overruns to judge, and no CPU clock to read (docs/performance.md
// "Simulator speed").
bool unpaced(const CliOptions& cli) { return cli.sim && cli.speed <= 0.0; }

rt::CycleConfig cycleConfig(const CliOptions& cli, const Settings& settings) {
  rt::CycleConfig c;
  c.rowPeriod = cli.telemetryCsv ? fromSec(1.0 / cli.telemetryRateHz) : 0;
  c.blockOnFullRows = unpaced(cli);
  if (unpaced(cli)) c.thinForUnpacedRun();
  c.rpmFromN2k = settings.can.RpmSource == "n2k";  // engine speed from the CAN service (docs/integrations.md)
  return c;
}

rt::LoopConfig loopConfig(const CliOptions& cli, const Settings& settings, const StartState& start,
                          DaemonRig& rig) {
  rt::LoopConfig c;
  c.period = fromUs(settings.runtime.control_period_us);
  if (cli.durationS)
    c.duration = fromSec(*cli.durationS);
  else if (unpaced(cli))
    c.duration = fromSec(start.scenario->duration_s);
  c.wallDeadlineOf = rig.wallDeadlineOf();
  c.wall = &rig.wall();
  if (!unpaced(cli)) c.cpuTime = [] { return rt::threadCpuTime(); };
  return c;
}

}  // namespace

int Daemon::run() {
  Settings settings = config_.settings;  // a scenario's [weather] may add to it
  const auto kernel = rt::detectPreemptRt();
  spdlog::info("xregulatord {} starting ({}), kernel {}: PREEMPT_RT {} ({})", XR_VERSION_STRING,
               cli_.sim ? "simulation" : "board", kernel.release, kernel.preemptRt ? "yes" : "no",
               kernel.how);
  StartState start = loadStartState(config_, cli_, settings);  // parameters and the state database
  if (start.exitCode != 0) return start.exitCode;
  const Params& params = start.running;

  Regulator regulator(params);
  if (start.restored) regulator.restoreLedger(*start.restored);
  rt::RegulatorCore core(regulator);
  auto handoffs = std::make_unique<rt::Handoffs>(params);
  // One clock (docs/architecture.md): in simulation the store, the events and
  // the summaries read the simulated time since the loop started.
  if (cli_.sim)
    start.clock.followSimulation(
        [&h = *handoffs] {
          const rt::RuntimeSnapshot s = h.latest();
          return s.tick > 0 ? s.telemetry.now - s.start : TimeNs{0};
        },
        cli_.speed);
  if (start.store) start.store->useClock(start.clock, cli_.speed);
  OutputFiles files;
  if (!openOutputFiles(cli_, *handoffs, files)) return kExitConfig;
  const auto rig = DaemonRig::open(start, settings, cli_, *handoffs, files.canLog);
  if (!rig) return kExitUnavailable;
  rt::fatal::install();

  // From here every object stops in reverse order on the way out: the
  // control thread, the services, then the rig's devices.
  rt::LoopStats stats;
  rt::ControlCycle cycle(core, rig->devices(), *handoffs, stats, rig->wall(), cycleConfig(cli_, settings));
  cycle.driveSafeState();  // field known LOW before anything runs
  rig->startSensors(voltageHardwareLimit(params));
  DaemonServices services(cli_, start, settings, *handoffs, *rig, std::move(files.csv),
                          std::move(files.canLog));
  rt::ControlLoop loop(cycle, rig->loopClock(), stats, loopConfig(cli_, settings, start, *rig));
  ControlThread control(loop, cycle, settings.runtime, !unpaced(cli_));
  sd_notify(0, "READY=1\nSTATUS=control loop running, field enable LOW until the regulator enables it");

  int exitCode = 0;
  try {
    exitCode = Supervisor(cli_, settings, loop, control, *handoffs, services, start.store.get(),
                          rig->pairingButton())
                   .run();
  } catch (const std::exception& e) {
    // Safe state first, then tell; the watchdog stays armed (an unclean stop).
    rt::fatal::driveSafeNow();
    loop.requestAbort();
    spdlog::critical("fatal: {}: field enable LOW, duty 0", e.what());
    control.join();
    cycle.driveSafeState();
    rt::fatal::driveSafeNow();  // the last write wins: the mirror says via=fatal
    return kExitSoftware;
  }
  control.join();
  if (control.failed()) {
    spdlog::critical("control thread failed: {}: field enable LOW, duty 0", control.error());
    exitCode = kExitSoftware;
  } else {
    rig->markCleanStop();  // the field is off: only now may the watchdog be disarmed
    spdlog::info("stopped cleanly: field enable LOW, duty 0");
  }
  const rt::RuntimeSnapshot last = handoffs->latest();
  // The control thread has ended: its statistics can be read directly (the
  // published summary is refreshed only every 64 ticks).
  logLoopStats(stats.summary(), cycle.health());
  services.stop();
  if (start.store) start.store->stop(handoffs->ledger.load(), last.tick > 100);
  return exitCode;
}

}  // namespace xr::app
