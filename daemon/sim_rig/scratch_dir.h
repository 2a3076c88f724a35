#pragma once
// Where a simulation keeps its 1-Wire sysfs tree: tmpfs when there is one,
// so a reading rewritten every 750 ms of virtual time never reaches a disk
// (when w1_slave was replaced by rename, ext4 forced a writeback each time,
// which dominated long runs and stalled real-time runs for tens of ms).
#include <stdlib.h>

#include <filesystem>
#include <string>

namespace xr::sim {

// A new private directory `<tmpfs or TMPDIR>/<prefix>XXXXXX`; empty on failure.
inline std::filesystem::path makeScratchDir(const char* prefix) {
  std::error_code ec;
  const std::filesystem::path base = std::filesystem::is_directory("/dev/shm", ec)
                                         ? std::filesystem::path("/dev/shm")
                                         : std::filesystem::temp_directory_path(ec);
  std::string tmpl = (base / (std::string(prefix) + "XXXXXX")).string();
  if (::mkdtemp(tmpl.data()) == nullptr) return {};
  return tmpl;
}

}  // namespace xr::sim
