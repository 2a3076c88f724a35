#pragma once
// Where a simulation keeps its 1-Wire sysfs tree: tmpfs when there is one.
// On ext4 each atomic replace of w1_slave (rename over an existing file)
// forces a data writeback: that dominated long runs and, in real-time runs,
// stalled the control thread for tens of milliseconds.
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
