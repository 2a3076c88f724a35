#include "app/update_watch.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace xr::app {

ReleaseInfo readReleaseFile(const std::string& path) {
  ReleaseInfo r;
  std::ifstream in(path);
  if (!in) return r;
  std::string line;
  while (std::getline(in, line)) {
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = line.substr(0, eq);
    const std::string value = line.substr(eq + 1);
    if (key == "version") r.version = value;
    if (key == "channel") r.channel = value;
    if (key == "installed_at") r.installedAt = value;
    if (key == "previous") r.previous = value;
  }
  r.known = !r.version.empty();
  return r;
}

std::string versionText(const char* buildVersion, const ReleaseInfo& r) {
  std::string s = std::string("xregulatord ") + buildVersion;
  if (!r.known) return s + " (not installed from a package)";
  return s + " (package " + r.version + ", channel " + (r.channel.empty() ? "none" : r.channel) +
         ", installed " + (r.installedAt.empty() ? "unknown" : r.installedAt) + ")";
}

bool boatBusy(const Telemetry& t) { return t.rpm >= kEngineTurningRpm || t.field_enable || t.duty_pct > 0.0; }

UpdateWatch::UpdateWatch(std::string releaseFile, std::string runDir, bool restartWhenQuiet)
    : releaseFile_(std::move(releaseFile)), runDir_(std::move(runDir)), restartWhenQuiet_(restartWhenQuiet) {
  running_ = readReleaseFile(releaseFile_);
  installed_ = running_;
}

bool UpdateWatch::poll(const Telemetry& t, std::uint64_t tick, std::int64_t unixMs) {
  writeState(t, tick, unixMs);
  const ReleaseInfo onDisk = readReleaseFile(releaseFile_);
  const bool busy = boatBusy(t);
  std::lock_guard lock(mu_);
  installed_ = onDisk;
  quietS_ = busy ? 0 : quietS_ + 1;
  const bool pending = onDisk.known && onDisk.version != running_.version;
  if (!pending) return false;
  if (!pendingLogged_) {
    pendingLogged_ = true;
    spdlog::warn("update: version {} installed while {} runs; it starts when the engine stops{}",
                 onDisk.version, running_.known ? running_.version : "an unpackaged build",
                 restartWhenQuiet_ ? "" : " (restart the service then)");
  }
  if (!restartWhenQuiet_ || quietS_ < kQuietSecondsBeforeRestart) return false;
  spdlog::warn(
      "update: engine stopped and field off for {} s: stopping (field enable LOW) so that version {} starts; "
      "exit 75",
      quietS_, onDisk.version);
  return true;
}

// Atomically (write, then rename) so the gate never reads half a file. The
// directory is made by systemd (RuntimeDirectory=): without it nothing is
// written, so a development run never litters /run.
void UpdateWatch::writeState(const Telemetry& t, std::uint64_t tick, std::int64_t unixMs) {
  std::error_code ec;
  if (runDir_.empty() || !std::filesystem::is_directory(runDir_, ec)) return;
  const std::string path = runDir_ + "/state";
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << "pid=" << ::getpid() << "\nupdated_ms=" << unixMs << "\ntick=" << tick
        << "\nengine_running=" << (t.rpm >= kEngineTurningRpm)
        << "\nfield_on=" << (t.field_enable || t.duty_pct > 0.0) << "\nrpm=" << static_cast<long>(t.rpm)
        << "\nversion=" << running_.version << "\n";
    if (!out) ec = std::make_error_code(std::errc::io_error);
  }
  if (!ec) std::filesystem::rename(tmp, path, ec);
  if (ec && !stateWarned_) {
    stateWarned_ = true;
    spdlog::error("update: cannot write {}: {}; the update gate will refuse updates", path, ec.message());
  }
}

void UpdateWatch::addTo(web::VersionMap& v) const {
  std::lock_guard lock(mu_);
  if (!running_.known) {
    v["package"] = "not installed from a package";
    return;
  }
  v["package"] = running_.version;
  v["channel"] = running_.channel.empty() ? "none" : running_.channel;
  v["installed"] = running_.installedAt;
  if (installed_.known && installed_.version != running_.version)
    v["update"] = "Update installed; starts when the engine stops (" + installed_.version + ")";
  else
    v["update"] = "none pending";
}

}  // namespace xr::app
