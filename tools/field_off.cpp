// xregulator-field-off: leaves the alternator field OFF. Run by systemd as
// ExecStartPre= and ExecStopPost= of xregulatord.service, so the field enable
// is LOW even when the daemon crashed or was killed ("ExecStopPost
// leaves the field enable LOW even if the daemon died").
//
//   xregulator-field-off [--config FILE]
//
// Exit 0 when the enable line was driven to its inactive level, 1 otherwise.
#include <gpiod.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

#include "config/config.h"
#include "field_off_plan.h"

namespace {

bool driveInactive(const xr::FieldOffPlan& plan, std::string& error) {
  gpiod_chip* chip = gpiod_chip_open_lookup(plan.gpioChip.c_str());
  if (!chip) {
    error = "cannot open GPIO chip " + plan.gpioChip + ": " + std::strerror(errno);
    return false;
  }
  bool ok = false;
  gpiod_line* line = gpiod_chip_get_line(chip, static_cast<unsigned>(plan.enableLine));
  if (!line) {
    error =
        "no line " + std::to_string(plan.enableLine) + " on " + plan.gpioChip + ": " + std::strerror(errno);
  } else if (gpiod_line_request_output(line, "xregulator-field-off", plan.inactiveLevel) != 0) {
    error = "cannot drive line " + std::to_string(plan.enableLine) + ": " + std::strerror(errno);
  } else {
    // request_output already set the level; set it again in case the driver
    // ignored the default value.
    ok = gpiod_line_set_value(line, plan.inactiveLevel) == 0;
    if (!ok) error = std::string("cannot set the line: ") + std::strerror(errno);
    gpiod_line_release(line);
  }
  gpiod_chip_close(chip);
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  std::string config = "/etc/xregulator/xregulator.toml";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--config" && i + 1 < argc) {
      config = argv[++i];
    } else if (a == "--help" || a == "-h") {
      std::cout << "usage: xregulator-field-off [--config FILE]\n"
                   "Drives the field enable line to its inactive level and the PWM duty to 0.\n";
      return 0;
    } else {
      std::cerr << "xregulator-field-off: unknown argument " << a << "\n";
      return 2;
    }
  }
  const xr::FieldOffPlan plan = xr::planFieldOff(xr::loadConfigFile(config));
  for (const auto& w : plan.warnings) std::cerr << "xregulator-field-off: " << w << "\n";

  // Best effort: zero the duty too (the enable line is the real cut).
  if (std::ofstream duty(plan.pwmDutyPath); duty) duty << "0\n";

  std::string error;
  if (!driveInactive(plan, error)) {
    std::cerr << "xregulator-field-off: FIELD ENABLE NOT DRIVEN: " << error << "\n";
    return 1;
  }
  std::cerr << "xregulator-field-off: field enable " << plan.gpioChip << " line " << plan.enableLine
            << " set to " << plan.inactiveLevel << " (field off)\n";
  return 0;
}
