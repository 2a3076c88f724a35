#include "drivers/watchdog/linux_watchdog.h"

#include <fcntl.h>
#include <linux/watchdog.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace xr {

LinuxWatchdog::~LinuxWatchdog() {
  // No magic close here: an object destroyed on an unclean path leaves the
  // watchdog armed, so the board resets if nothing else takes over.
  if (fd_ >= 0) ::close(fd_);
}

bool LinuxWatchdog::open(const std::string& path, int timeoutS) {
  error_.clear();
  warning_.clear();
  if (timeoutS < 1) {
    error_ = "watchdog: timeout must be >= 1 s";
    return false;
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd_ < 0) {
    const int e = errno;
    error_ = "watchdog: cannot open " + path + ": " + std::strerror(e);
    if (e == EACCES) error_ += " (run as root or grant the service user access to " + path + ")";
    if (e == ENOENT) error_ += " (enable it with 'dtparam=watchdog=on' in /boot/firmware/config.txt)";
    if (e == EBUSY) error_ += " (another process, e.g. systemd's RuntimeWatchdogSec, holds it)";
    return false;
  }
  int t = timeoutS;
  if (::ioctl(fd_, WDIOC_SETTIMEOUT, &t) < 0) {
    const int e = errno;
    if (e != ENOTTY) {
      error_ = "watchdog: WDIOC_SETTIMEOUT failed on " + path + ": " + std::strerror(e);
      closeClean();
      return false;
    }
    warning_ = "watchdog: " + path + " does not support WDIOC_SETTIMEOUT (not a watchdog device?)";
    timeoutS_ = timeoutS;
    return true;
  }
  int back = 0;
  if (::ioctl(fd_, WDIOC_GETTIMEOUT, &back) == 0) t = back;
  timeoutS_ = t;
  // Hardware may round (the BCM2835 caps at 15 s): report what it took.
  if (t != timeoutS) {
    warning_ =
        "watchdog: requested " + std::to_string(timeoutS) + " s, device uses " + std::to_string(t) + " s";
  }
  return true;
}

bool LinuxWatchdog::keepAlive() noexcept {
  if (fd_ < 0) return false;
  const char c = '\0';  // any byte but 'V' (which would arm the magic close)
  if (::write(fd_, &c, 1) != 1) return false;
  ++keepAlives_;
  return true;
}

void LinuxWatchdog::closeClean() noexcept {
  if (fd_ < 0) return;
  const char v = 'V';
  [[maybe_unused]] const auto n = ::write(fd_, &v, 1);
  ::close(fd_);
  fd_ = -1;
}

}  // namespace xr
