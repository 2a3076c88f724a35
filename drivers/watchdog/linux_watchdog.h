#pragma once
// LinuxWatchdog (docs/install.md, wiring): open the device (default /dev/watchdog,
// tests use a temp file), WDIOC_SETTIMEOUT with read-back, keepAlive() after
// each healthy control cycle (the runtime decides "healthy": a stalled loop
// stops feeding and the board resets), magic close 'V' only via closeClean()
// on a clean stop after the field is off. Destroying the object without
// closeClean() closes WITHOUT the magic character, so the watchdog keeps
// running and a crash still ends in a reset.
#include <string>

#include "drivers/hal/outputs.h"

namespace xr {

class LinuxWatchdog final : public Watchdog {
 public:
  LinuxWatchdog() = default;
  ~LinuxWatchdog() override;
  LinuxWatchdog(const LinuxWatchdog&) = delete;
  LinuxWatchdog& operator=(const LinuxWatchdog&) = delete;

  // Not RT. Opens `path` and sets the timeout (s). Returns true when the
  // device is open; a device that does not support the ioctls (ENOTTY, e.g.
  // a plain file in tests) is accepted but reported in `warning()`.
  bool open(const std::string& path, int timeoutS);
  const std::string& error() const noexcept { return error_; }
  const std::string& warning() const noexcept { return warning_; }
  int timeoutS() const noexcept { return timeoutS_; }  // read back (or requested when unsupported)
  bool isOpen() const noexcept { return fd_ >= 0; }

  // RT path: one write of a keep-alive byte ('\0', never 'V'). Returns false on error.
  bool keepAlive() noexcept override;
  // Writes 'V' then closes: the driver disarms. Only on a clean stop.
  void closeClean() noexcept override;
  unsigned long keepAlives() const noexcept { return keepAlives_; }
  int fd() const noexcept { return fd_; }

 private:
  int fd_ = -1;
  int timeoutS_ = 0;
  unsigned long keepAlives_ = 0;
  std::string error_, warning_;
};

}  // namespace xr
