#pragma once
// Loading and checking xregulator.toml (docs/configuration.md).
//
// Every error of a file is collected, never only the first: TOML syntax errors
// name file:line:column, unknown keys name the closest known key, wrong types
// and out-of-range values name key, value, allowed range and unit.
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "config/settings.h"

namespace xr {

// sysexits.h EX_CONFIG: the daemon does not start on a bad configuration.
inline constexpr int kExitConfig = 78;

struct ConfigError {
  std::string file;     // file name or the name given to loadConfigString
  int line = 0;         // 1-based; 0 when unknown
  int column = 0;       // 1-based; 0 when unknown
  std::string key;      // dotted key ("voltage.BulkVoltage"); empty for syntax errors
  std::string message;  // the explanation, without the location
  // "file:line:column: key: message" (parts that are unknown are left out).
  std::string toString() const;
};

struct LoadResult {
  std::optional<Config> config;     // set only when errors is empty
  std::vector<ConfigError> errors;  // ALL problems found
  bool ok() const { return config.has_value() && errors.empty(); }
};

// Parse and validate a configuration file. Missing keys keep their defaults
// (the catalogue's and Settings'); a missing file is an error.
LoadResult loadConfigFile(const std::string& path);
// Same, from text; name is used in error locations.
LoadResult loadConfigString(std::string_view text, std::string_view name);

// Exactly the content of config/xregulator.toml, embedded at build time, so
// `--print-default-config` prints that file byte for byte.
std::string_view defaultConfigText();

// `xregulatord --config FILE --check-config`: prints "FILE: OK" to out, or
// every error (one per line) to err. Returns 0 or kExitConfig (78).
int checkConfigMain(const std::string& path, std::ostream& out, std::ostream& err);

// Cross-parameter checks that no single range can express (FloatVoltage <=
// AbsorptionVoltage <= BulkVoltage, MinDuty <= MaxDuty, ascending RPM points,
// VoltageAlarmLow < VoltageAlarmHigh, ...). Empty when consistent.
std::vector<ConfigError> checkConsistency(const Params& p, std::string_view file = {});

}  // namespace xr
