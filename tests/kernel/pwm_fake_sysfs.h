#pragma once
// PwmSysfs against a tmpfs tree shaped like /sys/class/pwm, for the kernel
// rig (docs/development.md): the Debian arm64 kernel has no software PWM chip, so a
// thread plays the kernel's part (writing N to pwmchip0/export creates pwmN
// with period, duty_cycle, polarity and enable) and records, with inotify, the
// order in which the driver writes the attributes.
#include <string>

namespace xr::kernelrig {

// Runs the driver through open, 50 % duty, enable and the fatal-path safe
// state on ROOT (an empty directory). Prints one line per check; returns 0
// when every check holds.
int pwmCheck(const std::string& root);

}  // namespace xr::kernelrig
