#pragma once
// xregulatord command line (docs/xregulatord.8):
//   xregulatord [--config FILE] [--sim] [--scenario FILE] [--speed X|max]
//     [--duration S] [--telemetry-csv FILE] [--telemetry-rate HZ]
//     [--http ADDR:PORT] [--state-db FILE] [--check-config]
//     [--print-default-config] [--probe] [--version] [--seed N]
//     [--log-level L] [--sim-outputs FILE] [--can-log FILE]
// Both "--opt value" and "--opt=value" are accepted. A bad argument is a
// usage error: exit 64 (EX_USAGE) with a message naming it.
#include <optional>
#include <string>
#include <vector>

namespace xr::app {

inline constexpr int kExitUsage = 64;        // EX_USAGE
inline constexpr int kExitSoftware = 70;     // EX_SOFTWARE: internal error (exception)
inline constexpr int kExitUnavailable = 69;  // EX_UNAVAILABLE: hardware missing
inline constexpr int kExitTempFail = 75;     // EX_TEMPFAIL: another daemon holds the state database

// The package's paths for updates (app/update_watch.h): its release record,
// and the directory of the quiet state file the update gate reads.
inline constexpr const char* kDefaultReleaseFile = "/var/lib/xregulator/release";
inline constexpr const char* kDefaultRunDir = "/run/xregulator";

// Test-only faults (hidden, accepted only with --sim): end the daemon by a
// given path at a given simulated time so tests/e2e can prove each exit path
// leaves the field off.
enum class TestFault { None, Segv, Abort, Throw, Terminate, ThrowInControl };

struct CliOptions {
  std::optional<std::string> config;
  bool sim = false;
  std::optional<std::string> scenario;
  double speed = 1.0;  // 0 = max
  bool speedGiven = false;
  std::optional<double> durationS;
  std::optional<std::string> telemetryCsv;
  double telemetryRateHz = 10.0;
  std::optional<std::string> http;
  std::optional<std::string> stateDb;
  bool checkConfig = false;
  bool printToken = false;
  bool pair = false;  // --pair: a new pairing code from the running daemon
  bool printDefaultConfig = false;
  bool printConfig =
      false;  // --print-config: the effective configuration with sources (docs/configuration.md)
  bool probe = false;
  bool version = false;
  bool help = false;
  std::optional<unsigned long long> seed;
  std::optional<std::string> logLevel;
  std::optional<std::string> simOutputs;
  std::optional<std::string> canLog;  // candump log of every CAN frame (docs/integrations.md)
  // Updates (app/update_watch.h): the package's release record, the quiet
  // state file's directory, and whether a pending update restarts when quiet.
  std::string releaseFile = kDefaultReleaseFile;
  // Empty: no state file. parseCommandLine() sets the board's default,
  // /run/xregulator, unless --run-dir is given or the daemon runs --sim: a
  // simulated engine must never speak for the real one to the update gate.
  std::string runDir;
  bool updateWatch = false;
  TestFault testFault = TestFault::None;
  double testFaultAtS = 1.0;
};

struct CliResult {
  CliOptions options;
  std::string error;  // non-empty: refused, exit with exitCode
  // 64 (EX_USAGE) for a usage error; 78 (EX_CONFIG) for a value the config
  // file would refuse too (--http), so both exit alike.
  int exitCode = kExitUsage;  // or kExitConfig (config/config.h)
  bool ok() const { return error.empty(); }
};

CliResult parseCommandLine(const std::vector<std::string>& args);
std::string usageText();

}  // namespace xr::app
