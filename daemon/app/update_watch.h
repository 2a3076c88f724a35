#pragma once
// Updates that wait for a quiet boat (docs/operations.md "Updates and the way back").
//
// The package's postinst writes a release file (version, channel, install
// time, the version it replaced) into the state directory. The daemon reads
// it at start (what --version, /api/system and the System page show) and
// again every second: when the file names another version, the package was
// upgraded under a running daemon, which then says "Update installed; starts
// when the engine stops" and, with --update-watch, stops through the
// controlled ramp (field enable LOW) with exit 75 once the boat has been
// quiet for kQuietSecondsBeforeRestart, so that systemd starts the new binary.
//
// Every second it also writes the quiet state file <run-dir>/state that the
// package's pre-install gate (tools/update/xregulator-update-gate) reads: the
// gate refuses an upgrade while the engine turns or the field is on.
#include <cstdint>
#include <mutex>
#include <string>

#include "control/telemetry.h"
#include "web/server/daemon_api.h"

namespace xr::app {

// The package's release record (key=value lines); known = the file was read.
struct ReleaseInfo {
  bool known = false;
  std::string version;
  std::string channel;
  std::string installedAt;
  std::string previous;
};

// An engine below this speed is stopped (a tach's noise at rest is far lower).
inline constexpr double kEngineTurningRpm = 50.0;
// A boat must stay quiet this long before a pending update restarts the
// daemon: an engine that stalls and is restarted at once is not "stopped".
inline constexpr int kQuietSecondsBeforeRestart = 10;

ReleaseInfo readReleaseFile(const std::string& path);
// "xregulatord 0.1.0 (package 0.1.0-2, channel stable, installed 2026-...)".
std::string versionText(const char* buildVersion, const ReleaseInfo& r);
// The engine turns or the field is on: no update may start now.
bool boatBusy(const Telemetry& t);

class UpdateWatch {
 public:
  UpdateWatch(std::string releaseFile, std::string runDir, bool restartWhenQuiet);
  // Once a second from the supervisor. True: stop now so that the installed
  // version starts (only with restartWhenQuiet).
  bool poll(const Telemetry& t, std::uint64_t tick, std::int64_t unixMs);
  // Adds package, channel, installed and update to /api/system's versions.
  void addTo(web::VersionMap& v) const;

 private:
  void writeState(const Telemetry& t, std::uint64_t tick, std::int64_t unixMs);

  const std::string releaseFile_;
  const std::string runDir_;
  const bool restartWhenQuiet_;
  mutable std::mutex mu_;
  ReleaseInfo running_;    // read at start: the version this process is
  ReleaseInfo installed_;  // read last: the version on disk
  int quietS_ = 0;
  bool pendingLogged_ = false;
  bool stateWarned_ = false;
};

}  // namespace xr::app
