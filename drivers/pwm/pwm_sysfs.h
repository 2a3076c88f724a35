#pragma once
// PwmSysfs (docs/install.md, wiring): the PwmOutput seam on
// <root>/pwmchipN/pwmM (root "/sys/class/pwm" on the board; tests use a fake
// tree). open(): export if needed, disable, set `period` from the frequency,
// duty 0, `polarity`; keeps duty_cycle and enable open and writes them with
// pwrite (RT path: no allocation, no exceptions). A missing chip gives an
// error that names the overlay to enable.
#include <string>

#include "drivers/hal/outputs.h"

namespace xr {

// Pre-opened descriptors and async-signal-safe writes (only pwrite), for the
// runtime's fatal-signal / std::terminate handlers: drive duty 0 and
// enable 0 without touching the heap or locks. Copyable plain data.
struct PwmSafeStateWriter {
  int dutyFd = -1;
  int enableFd = -1;
  bool truncate = false;  // regular files (a fake tree): cut stale trailing bytes
  // Writes duty_cycle 0 then enable 0. Returns true when both writes succeeded.
  bool driveSafe() const noexcept;
};

class PwmSysfs final : public PwmOutput {
 public:
  PwmSysfs() = default;
  ~PwmSysfs() override;
  PwmSysfs(const PwmSysfs&) = delete;
  PwmSysfs& operator=(const PwmSysfs&) = delete;

  // Not RT. Returns true on success; on failure `error()` tells the user what
  // to fix (e.g. "add dtoverlay=pwm,pin=18,func=2 to /boot/config.txt").
  bool open(const std::string& root, int chip, int channel, double frequencyHz, bool inverted);
  const std::string& error() const noexcept { return error_; }
  bool isOpen() const noexcept { return dutyFd_ >= 0; }

  // RT path. duty in % (clamped to 0..100, NaN -> 0); writes duty_cycle in ns.
  bool setDutyPercent(double pct) noexcept override;
  bool setEnabled(bool on) noexcept override;
  long periodNs() const noexcept { return periodNs_; }

  PwmSafeStateWriter safeStateWriter() const noexcept { return {dutyFd_, enableFd_, truncate_}; }
  void close() noexcept;

  // Duty in ns for a percentage of a period (pure; clamps and maps NaN to 0).
  static long dutyNsFor(double pct, long periodNs) noexcept;

 private:
  int dutyFd_ = -1;
  int enableFd_ = -1;
  long periodNs_ = 0;
  long lastDutyNs_ = -1;
  bool truncate_ = false;
  std::string dir_;
  std::string error_;
};

// Writes a small decimal/text value with pwrite at offset 0
// (async-signal-safe). `truncate` also cuts the file to that length, for
// regular files standing in for sysfs attributes in tests.
bool pwriteText(int fd, const char* text, bool truncate = false) noexcept;
bool pwriteLong(int fd, long v, bool truncate = false) noexcept;

}  // namespace xr
