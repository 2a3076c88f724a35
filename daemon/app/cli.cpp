#include "app/cli.h"

#include <charconv>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "config/config.h"
#include "config/web_checks.h"

namespace xr::app {

namespace {

bool parseDouble(const std::string& s, double& out) {
  if (s.empty()) return false;
  try {
    std::size_t pos = 0;
    out = std::stod(s, &pos);
    return pos == s.size() && std::isfinite(out);
  } catch (...) {
    return false;
  }
}

bool parseUnsigned(const std::string& s, unsigned long long& out) {
  const auto* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, out);
  return ec == std::errc() && p == end && !s.empty();
}

}  // namespace

std::string usageText() {
  return "usage: xregulatord [--config FILE] [--sim] [--scenario FILE] [--speed X|max]\n"
         "                   [--duration S] [--telemetry-csv FILE] [--telemetry-rate HZ]\n"
         "                   [--http ADDR:PORT] [--state-db FILE] [--check-config]\n"
         "                   [--print-default-config] [--probe] [--version] [--seed N]\n"
         "                   [--log-level L] [--sim-outputs FILE] [--print-token] [--pair]\n"
         "                   [--print-config] [--can-log FILE] [--update-watch]\n"
         "                   [--release-file FILE] [--run-dir DIR]\n"
         "\n"
         "  --config FILE          configuration (default: built-in defaults; the service uses\n"
         "                         /etc/xregulator/xregulator.toml)\n"
         "  --sim                  simulated hardware: the real drivers on a simulated I2C bus\n"
         "  --scenario FILE        scenario TOML for --sim (default: built-in scenario)\n"
         "  --speed X|max          simulation speed: 1 = real time, 10 = ten times, max = unpaced\n"
         "  --duration S           stop after S seconds (simulated time in --sim)\n"
         "  --telemetry-csv FILE   write telemetry rows to FILE\n"
         "  --telemetry-rate HZ    CSV row rate (default 10, simulated time in --sim)\n"
         "  --http ADDR:PORT       dashboard and API address (default from [web])\n"
         "  --state-db FILE        SQLite state database (default from [store]; none in --sim)\n"
         "  --check-config         validate --config, with the overrides stored in the state\n"
         "                         database, and exit (0 or 78)\n"
         "  --print-token          print the API write token kept in the state database\n"
         "  --pair                 ask the running daemon for a new phone pairing code\n"
         "                         (needs --config FILE, or --http ADDR:PORT and --state-db FILE)\n"
         "  --print-default-config print the documented default configuration\n"
         "  --print-config         print the effective configuration (--config, battery profile and\n"
         "                         stored dashboard settings), each value with its source\n"
         "  --probe                check the hardware and print what to fix\n"
         "  --version              print the version\n"
         "  --seed N               simulation randomness seed (overrides the scenario's)\n"
         "  --log-level L          trace|debug|info|warn|error|critical|off\n"
         "  --sim-outputs FILE     --sim: mirror the last PWM duty / field enable / buzzer into FILE\n"
         "  --can-log FILE         write every CAN frame sent and received, on both buses, to FILE\n"
         "                         (candump log format; times since the start of the run in --sim)\n"
         "  --update-watch         when the package was upgraded under this daemon, stop (field off,\n"
         "                         exit 75) once the engine is stopped, so systemd starts the new one\n"
         "  --release-file FILE    the package's release record (default /var/lib/xregulator/release)\n"
         "  --run-dir DIR          where the quiet state file for the update gate is written, if the\n"
         "                         directory exists (default /run/xregulator; none in --sim)\n";
}

namespace {

using Flags = std::map<std::string, std::function<void()>>;
// An option with a value: an error text, or "" when taken.
using Setter = std::function<std::string(const std::string&)>;
using Valued = std::map<std::string, Setter>;

Setter textInto(std::optional<std::string>& field) {
  return [&field](const std::string& v) {
    field = v;
    return std::string();
  };
}

Flags flagOptions(CliOptions& o) {
  return {
      {"--sim", [&o] { o.sim = true; }},
      {"--check-config", [&o] { o.checkConfig = true; }},
      {"--print-token", [&o] { o.printToken = true; }},
      {"--pair", [&o] { o.pair = true; }},
      {"--print-default-config", [&o] { o.printDefaultConfig = true; }},
      {"--print-config", [&o] { o.printConfig = true; }},
      {"--probe", [&o] { o.probe = true; }},
      {"--version", [&o] { o.version = true; }},
      {"--update-watch", [&o] { o.updateWatch = true; }},
      {"--help", [&o] { o.help = true; }},
      {"-h", [&o] { o.help = true; }},
  };
}

// Files, addresses and the log level.
Valued textOptions(CliResult& r, bool& runDirGiven) {
  CliOptions& o = r.options;
  Valued v = {{"--config", textInto(o.config)},
              {"--scenario", textInto(o.scenario)},
              {"--telemetry-csv", textInto(o.telemetryCsv)},
              {"--state-db", textInto(o.stateDb)},
              {"--log-level", textInto(o.logLevel)},
              {"--sim-outputs", textInto(o.simOutputs)},
              {"--can-log", textInto(o.canLog)}};
  v["--release-file"] = [&o](const std::string& t) {
    o.releaseFile = t;
    return std::string();
  };
  v["--run-dir"] = [&r, &runDirGiven](const std::string& t) {
    r.options.runDir = t;
    runDirGiven = true;
    return std::string();
  };
  v["--http"] = [&r](const std::string& text) {
    r.options.http = text;
    // Checked here, before any device opens, by the check [web] listen
    // gets: a bad value exits 78, it never runs without the dashboard.
    if (auto why = checkHttpListenText(text); !why.empty()) {
      r.exitCode = kExitConfig;
      return "--http: " + why;
    }
    return std::string();
  };
  return v;
}

// The simulation's pace, length, output rate and random seed.
void addRunOptions(CliOptions& o, Valued& v) {
  v["--speed"] = [&o](const std::string& text) {
    o.speedGiven = true;
    double d = 0.0;
    if (text == "max") {
      o.speed = 0.0;
      return std::string();
    }
    if (!parseDouble(text, d) || d <= 0.0 || d > 1e6)
      return "--speed: expected a positive number or 'max', got '" + text + "'";
    o.speed = d;
    return std::string();
  };
  v["--duration"] = [&o](const std::string& text) {
    double d = 0.0;
    if (!parseDouble(text, d) || d <= 0.0) return "--duration: expected seconds > 0, got '" + text + "'";
    o.durationS = d;
    return std::string();
  };
  v["--telemetry-rate"] = [&o](const std::string& text) {
    double d = 0.0;
    if (!parseDouble(text, d) || d <= 0.0 || d > 400.0)
      return "--telemetry-rate: expected Hz in (0, 400], got '" + text + "'";
    o.telemetryRateHz = d;
    return std::string();
  };
  v["--seed"] = [&o](const std::string& text) {
    unsigned long long n = 0;
    if (!parseUnsigned(text, n)) return "--seed: expected a non-negative integer, got '" + text + "'";
    o.seed = n;
    return std::string();
  };
}

// The hidden faults that prove every exit path leaves the field off.
void addTestFaultOptions(CliOptions& o, bool& faultAtGiven, Valued& v) {
  v["--test-fault"] = [&o](const std::string& text) {
    static const std::map<std::string, TestFault> kinds = {{"segv", TestFault::Segv},
                                                           {"abort", TestFault::Abort},
                                                           {"throw", TestFault::Throw},
                                                           {"terminate", TestFault::Terminate},
                                                           {"throw-control", TestFault::ThrowInControl}};
    auto it = kinds.find(text);
    if (it == kinds.end()) return "--test-fault: unknown kind '" + text + "'";
    o.testFault = it->second;
    return std::string();
  };
  v["--test-fault-at"] = [&o, &faultAtGiven](const std::string& text) {
    double d = 0.0;
    if (!parseDouble(text, d) || d < 0.0) return "--test-fault-at: expected seconds >= 0, got '" + text + "'";
    o.testFaultAtS = d;
    faultAtGiven = true;
    return std::string();
  };
}

// Reads every argument; the first error ends it (in r.error).
void readArguments(const std::vector<std::string>& args, const Flags& flags, const Valued& valued,
                   CliResult& r) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string a = args[i];
    std::optional<std::string> inlineValue;
    if (a.rfind("--", 0) == 0) {
      if (const auto eq = a.find('='); eq != std::string::npos) {
        inlineValue = a.substr(eq + 1);
        a = a.substr(0, eq);
      }
    }
    if (auto f = flags.find(a); f != flags.end()) {
      if (inlineValue) {
        r.error = a + " takes no value";
        return;
      }
      f->second();
      continue;
    }
    auto v = valued.find(a);
    if (v == valued.end()) {
      r.error = (a.rfind("-", 0) == 0 ? "unknown option '" : "unexpected argument '") + a + "'";
      return;
    }
    if (!inlineValue && i + 1 >= args.size()) {
      r.error = a + " needs a value";
      return;
    }
    if (auto err = v->second(inlineValue ? *inlineValue : args[++i]); !err.empty()) {
      r.error = err;
      return;
    }
  }
}

// Options that need another: the first missing one, or "".
std::string combinationError(const CliOptions& o, bool faultAtGiven) {
  if (o.scenario && !o.sim) return "--scenario needs --sim";
  if (o.simOutputs && !o.sim) return "--sim-outputs needs --sim";
  if (o.speedGiven && !o.sim) return "--speed needs --sim";
  if (o.seed && !o.sim) return "--seed needs --sim";
  if (o.testFault != TestFault::None && !o.sim) return "--test-fault needs --sim";
  if (faultAtGiven && o.testFault == TestFault::None) return "--test-fault-at needs --test-fault";
  if (o.checkConfig && !o.config) return "--check-config needs --config FILE";
  if (o.printToken && !o.config && !o.stateDb) return "--print-token needs --state-db FILE or --config FILE";
  if (o.pair && !o.config && !(o.http && o.stateDb))
    return "--pair needs --config FILE (or --http ADDR:PORT and --state-db FILE)";
  return {};
}

}  // namespace

CliResult parseCommandLine(const std::vector<std::string>& args) {
  CliResult r;
  bool faultAtGiven = false, runDirGiven = false;
  Valued valued = textOptions(r, runDirGiven);
  addRunOptions(r.options, valued);
  addTestFaultOptions(r.options, faultAtGiven, valued);
  readArguments(args, flagOptions(r.options), valued, r);
  if (r.error.empty()) r.error = combinationError(r.options, faultAtGiven);
  // The update gate reads this directory's state file as the running
  // regulator's word (docs/operations.md "Updates and the way back").
  if (!runDirGiven && !r.options.sim) r.options.runDir = kDefaultRunDir;
  return r;
}

}  // namespace xr::app
