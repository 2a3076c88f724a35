#include "drivers/pwm/pwm_sysfs.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <string>

namespace xr {

namespace {
bool exists(const std::string& p) {
  struct stat st;
  return ::stat(p.c_str(), &st) == 0;
}
std::string errnoText(int e) { return std::string(std::strerror(e)); }
// Writes a whole small file once (open/pwrite/close); not RT.
int writeOnce(const std::string& path, const std::string& text, bool trunc) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return errno;
  const int rc = pwriteText(fd, text.c_str(), trunc) ? 0 : errno;
  ::close(fd);
  return rc;
}
constexpr const char* kOverlayHint =
    "enable the PWM overlay: add 'dtoverlay=pwm,pin=18,func=2' to /boot/firmware/config.txt "
    "(/boot/config.txt on older images) and reboot";
}  // namespace

bool pwriteText(int fd, const char* text, bool truncate) noexcept {
  if (fd < 0) return false;
  const std::size_t len = std::strlen(text);
  const ssize_t n = ::pwrite(fd, text, len, 0);
  if (n != static_cast<ssize_t>(len)) return false;
  if (truncate && ::ftruncate(fd, static_cast<off_t>(len)) != 0) return false;
  return true;
}

bool pwriteLong(int fd, long v, bool truncate) noexcept {
  // Hand-rolled formatting: snprintf is not async-signal-safe.
  char buf[24];
  char* p = buf + sizeof(buf);
  *--p = '\0';
  *--p = '\n';
  const bool neg = v < 0;
  unsigned long u = neg ? 0UL - static_cast<unsigned long>(v) : static_cast<unsigned long>(v);
  do {
    *--p = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u != 0);
  if (neg) *--p = '-';
  return pwriteText(fd, p, truncate);
}

bool PwmSafeStateWriter::driveSafe() const noexcept {
  const bool duty = pwriteText(dutyFd, "0\n", truncate);
  const bool en = pwriteText(enableFd, "0\n", truncate);
  return duty && en;
}

PwmSysfs::~PwmSysfs() {
  // Leave the field off when the object goes (the runtime normally already did).
  if (isOpen()) {
    safeStateWriter().driveSafe();
  }
  close();
}

void PwmSysfs::close() noexcept {
  if (dutyFd_ >= 0) ::close(dutyFd_);
  if (enableFd_ >= 0) ::close(enableFd_);
  dutyFd_ = enableFd_ = -1;
}

long PwmSysfs::dutyNsFor(double pct, long periodNs) noexcept {
  if (!(pct > 0.0)) return 0;  // also NaN
  if (pct >= 100.0) return periodNs;
  return std::lround(static_cast<double>(periodNs) * pct / 100.0);
}

bool PwmSysfs::open(const std::string& root, int chip, int channel, double frequencyHz, bool inverted) {
  close();
  error_.clear();
  if (!(frequencyHz > 0.0) || frequencyHz > 1.0e6) {
    error_ = "pwm: frequency " + std::to_string(frequencyHz) + " Hz is out of range (0 < f <= 1 MHz)";
    return false;
  }
  const std::string chipDir = root + "/pwmchip" + std::to_string(chip);
  if (!exists(chipDir)) {
    error_ = "pwm: " + chipDir + " not found; " + kOverlayHint;
    return false;
  }
  dir_ = chipDir + "/pwm" + std::to_string(channel);
  if (!exists(dir_)) {
    const int rc = writeOnce(chipDir + "/export", std::to_string(channel) + "\n", false);
    if (rc != 0) {
      error_ = "pwm: cannot export channel " + std::to_string(channel) + " via " + chipDir +
               "/export: " + errnoText(rc) +
               (rc == EACCES ? " (add the user to the 'gpio' group or run as root)" : "");
      return false;
    }
    // udev applies group permissions shortly after the export.
    for (int i = 0; i < 100 && !exists(dir_ + "/enable"); ++i) ::usleep(10'000);
    if (!exists(dir_)) {
      error_ = "pwm: " + dir_ + " did not appear after export; check that channel " +
               std::to_string(channel) + " exists on pwmchip" + std::to_string(chip) + " (" + kOverlayHint +
               ")";
      return false;
    }
  }
  struct stat st;
  truncate_ = ::stat((dir_ + "/duty_cycle").c_str(), &st) == 0 && S_ISREG(st.st_mode);
  dutyFd_ = ::open((dir_ + "/duty_cycle").c_str(), O_WRONLY | O_CLOEXEC);
  enableFd_ = ::open((dir_ + "/enable").c_str(), O_WRONLY | O_CLOEXEC);
  if (dutyFd_ < 0 || enableFd_ < 0) {
    const int e = errno;
    close();
    error_ = "pwm: cannot open " + dir_ + "/duty_cycle or enable: " + errnoText(e) +
             (e == EACCES ? " (add the user to the 'gpio' group or run as root)" : "");
    return false;
  }
  periodNs_ = std::lround(1.0e9 / frequencyHz);
  // Order matters for the kernel: disabled, duty 0 (<= any period), then the
  // period, then the polarity (only changeable while disabled).
  bool ok = pwriteText(enableFd_, "0\n", truncate_);
  ok = pwriteText(dutyFd_, "0\n", truncate_) && ok;
  int rc = writeOnce(dir_ + "/period", std::to_string(periodNs_) + "\n", truncate_);
  if (rc == 0) rc = writeOnce(dir_ + "/polarity", inverted ? "inversed\n" : "normal\n", truncate_);
  if (!ok || rc != 0) {
    error_ = "pwm: cannot configure " + dir_ + ": " + errnoText(rc != 0 ? rc : errno);
    close();
    return false;
  }
  lastDutyNs_ = 0;
  return true;
}

bool PwmSysfs::setDutyPercent(double pct) noexcept {
  if (dutyFd_ < 0) return false;
  const long ns = dutyNsFor(pct, periodNs_);
  if (ns == lastDutyNs_) return true;  // unchanged: no syscall
  if (!pwriteLong(dutyFd_, ns, truncate_)) {
    lastDutyNs_ = -1;  // unknown: write again next time
    return false;
  }
  lastDutyNs_ = ns;
  return true;
}

bool PwmSysfs::setEnabled(bool on) noexcept {
  if (enableFd_ < 0) return false;
  return pwriteText(enableFd_, on ? "1\n" : "0\n", truncate_);
}

}  // namespace xr
