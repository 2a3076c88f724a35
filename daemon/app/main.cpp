// xregulatord: alternator field regulator daemon. See docs/architecture.md for the
// command line and daemon/app/daemon.h for the exit paths.
#include <signal.h>

#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli.h"
#include "app/config_check.h"
#include "app/daemon.h"
#include "app/pair_cli.h"
#include "app/update_watch.h"
#include "config/config.h"
#include "drivers/probe/probe.h"
#include "logging/logging.h"
#include "runtime/fatal_guard.h"
#include "runtime/signals.h"

int main(int argc, char** argv) {
  using namespace xr;
  using namespace xr::app;

  // Every signal that would end the process is either blocked here, before
  // any thread exists so every thread inherits the mask, and taken
  // synchronously by the supervisor (sigtimedwait), or a fault handled by
  // fatal_guard (runtime/signals.h). SIGPIPE is ignored: a vanished web
  // client must not kill the regulator.
  rt::signals::blockWaitedSignals();

  const CliResult cli = parseCommandLine(std::vector<std::string>(argv + 1, argv + argc));
  if (!cli.ok()) {
    std::fprintf(stderr, "xregulatord: %s\n(run xregulatord --help for usage)\n", cli.error.c_str());
    return cli.exitCode;
  }
  const CliOptions& o = cli.options;
  if (o.help) {
    std::cout << usageText();
    return 0;
  }
  if (o.version) {
    std::cout << versionText(XR_VERSION_STRING, readReleaseFile(o.releaseFile)) << "\n";
    return 0;
  }
  if (o.printDefaultConfig) {
    std::cout << defaultConfigText();
    return 0;
  }
  if (o.checkConfig) return checkConfigAndState(*o.config, o.stateDb, std::cout, std::cerr);
  if (o.printToken) return printTokenMain(o.config, o.stateDb, std::cout, std::cerr);
  if (o.pair) return pairMain(o.config, o.stateDb, o.http, std::cout, std::cerr);
  if (o.printConfig) return printConfigMain(o.config, o.stateDb, std::cout, std::cerr);

  Config config;
  if (o.config) {
    LoadResult r = loadConfigFile(*o.config);
    if (!r.ok()) {
      for (const auto& e : r.errors) std::cerr << e.toString() << "\n";
      std::cerr << "xregulatord: configuration rejected; the field stays off\n";
      return kExitConfig;
    }
    config = std::move(*r.config);
  }
  if (auto err = initLogging(config.settings.log, o.logLevel); !err.empty()) {
    std::fprintf(stderr, "xregulatord: %s\n", err.c_str());
    return o.logLevel ? kExitUsage : kExitConfig;
  }
  if (o.probe) return runProbe(config.settings, std::cout);

  try {
    Daemon daemon(std::move(config), o);
    return daemon.run();
  } catch (const std::exception& e) {
    rt::fatal::driveSafeNow();
    std::fprintf(stderr, "xregulatord: fatal: %s (field enable LOW, duty 0)\n", e.what());
    return kExitSoftware;
  }
}
