#include "app/cli.h"

#include <charconv>
#include <cmath>
#include <functional>
#include <map>

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
         "                   [--print-config] [--can-log FILE]\n"
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
         "                         (candump log format; times since the start of the run in --sim)\n";
}

CliResult parseCommandLine(const std::vector<std::string>& args) {
  CliResult r;
  CliOptions& o = r.options;
  bool faultAtGiven = false;

  // Flags without a value.
  const std::map<std::string, std::function<void()>> flags = {
      {"--sim", [&] { o.sim = true; }},
      {"--check-config", [&] { o.checkConfig = true; }},
      {"--print-token", [&] { o.printToken = true; }},
      {"--pair", [&] { o.pair = true; }},
      {"--print-default-config", [&] { o.printDefaultConfig = true; }},
      {"--print-config", [&] { o.printConfig = true; }},
      {"--probe", [&] { o.probe = true; }},
      {"--version", [&] { o.version = true; }},
      {"--help", [&] { o.help = true; }},
      {"-h", [&] { o.help = true; }},
  };
  // Options with a value: return an error text or "".
  const std::map<std::string, std::function<std::string(const std::string&)>> valued = {
      {"--config",
       [&](const std::string& v) {
         o.config = v;
         return std::string();
       }},
      {"--scenario",
       [&](const std::string& v) {
         o.scenario = v;
         return std::string();
       }},
      {"--telemetry-csv",
       [&](const std::string& v) {
         o.telemetryCsv = v;
         return std::string();
       }},
      {"--http",
       [&](const std::string& v) {
         o.http = v;
         // Checked here, before any device opens, by the check [web] listen
         // gets: a bad value exits 78, it never runs without the dashboard.
         if (auto why = checkHttpListenText(v); !why.empty()) {
           r.exitCode = kExitConfig;
           return "--http: " + why;
         }
         return std::string();
       }},
      {"--state-db",
       [&](const std::string& v) {
         o.stateDb = v;
         return std::string();
       }},
      {"--log-level",
       [&](const std::string& v) {
         o.logLevel = v;
         return std::string();
       }},
      {"--sim-outputs",
       [&](const std::string& v) {
         o.simOutputs = v;
         return std::string();
       }},
      {"--can-log",
       [&](const std::string& v) {
         o.canLog = v;
         return std::string();
       }},
      {"--speed",
       [&](const std::string& v) {
         o.speedGiven = true;
         if (v == "max") {
           o.speed = 0.0;
           return std::string();
         }
         double d;
         if (!parseDouble(v, d) || d <= 0.0 || d > 1e6)
           return "--speed: expected a positive number or 'max', got '" + v + "'";
         o.speed = d;
         return std::string();
       }},
      {"--duration",
       [&](const std::string& v) {
         double d;
         if (!parseDouble(v, d) || d <= 0.0) return "--duration: expected seconds > 0, got '" + v + "'";
         o.durationS = d;
         return std::string();
       }},
      {"--telemetry-rate",
       [&](const std::string& v) {
         double d;
         if (!parseDouble(v, d) || d <= 0.0 || d > 400.0)
           return "--telemetry-rate: expected Hz in (0, 400], got '" + v + "'";
         o.telemetryRateHz = d;
         return std::string();
       }},
      {"--seed",
       [&](const std::string& v) {
         unsigned long long n;
         if (!parseUnsigned(v, n)) return "--seed: expected a non-negative integer, got '" + v + "'";
         o.seed = n;
         return std::string();
       }},
      {"--test-fault",
       [&](const std::string& v) {
         static const std::map<std::string, TestFault> kinds = {{"segv", TestFault::Segv},
                                                                {"abort", TestFault::Abort},
                                                                {"throw", TestFault::Throw},
                                                                {"terminate", TestFault::Terminate},
                                                                {"throw-control", TestFault::ThrowInControl}};
         auto it = kinds.find(v);
         if (it == kinds.end()) return "--test-fault: unknown kind '" + v + "'";
         o.testFault = it->second;
         return std::string();
       }},
      {"--test-fault-at",
       [&](const std::string& v) {
         double d;
         if (!parseDouble(v, d) || d < 0.0) return "--test-fault-at: expected seconds >= 0, got '" + v + "'";
         o.testFaultAtS = d;
         faultAtGiven = true;
         return std::string();
       }},
  };

  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string a = args[i];
    std::optional<std::string> inlineValue;
    if (a.rfind("--", 0) == 0) {
      const auto eq = a.find('=');
      if (eq != std::string::npos) {
        inlineValue = a.substr(eq + 1);
        a = a.substr(0, eq);
      }
    }
    if (auto f = flags.find(a); f != flags.end()) {
      if (inlineValue) {
        r.error = a + " takes no value";
        return r;
      }
      f->second();
      continue;
    }
    if (auto v = valued.find(a); v != valued.end()) {
      std::string value;
      if (inlineValue) {
        value = *inlineValue;
      } else if (i + 1 < args.size()) {
        value = args[++i];
      } else {
        r.error = a + " needs a value";
        return r;
      }
      if (auto err = v->second(value); !err.empty()) {
        r.error = err;
        return r;
      }
      continue;
    }
    r.error = (a.rfind("-", 0) == 0 ? "unknown option '" : "unexpected argument '") + a + "'";
    return r;
  }

  if (o.scenario && !o.sim)
    r.error = "--scenario needs --sim";
  else if (o.simOutputs && !o.sim)
    r.error = "--sim-outputs needs --sim";
  else if (o.speedGiven && !o.sim)
    r.error = "--speed needs --sim";
  else if (o.seed && !o.sim)
    r.error = "--seed needs --sim";
  else if (o.testFault != TestFault::None && !o.sim)
    r.error = "--test-fault needs --sim";
  else if (faultAtGiven && o.testFault == TestFault::None)
    r.error = "--test-fault-at needs --test-fault";
  else if (o.checkConfig && !o.config)
    r.error = "--check-config needs --config FILE";
  else if (o.printToken && !o.config && !o.stateDb)
    r.error = "--print-token needs --state-db FILE or --config FILE";
  else if (o.pair && !o.config && !(o.http && o.stateDb))
    r.error = "--pair needs --config FILE (or --http ADDR:PORT and --state-db FILE)";
  return r;
}

}  // namespace xr::app
