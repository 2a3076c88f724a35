#pragma once
// What xregulator-field-off must drive, worked out from the configuration
// file. A broken or missing file must not stop the field from being cut, so
// the plan then falls back to the built-in defaults and says so.
#include <string>
#include <vector>

#include "config/config.h"

namespace xr {

struct FieldOffPlan {
  std::string gpioChip;       // libgpiod lookup: name, path, label or number
  int enableLine = 4;
  int inactiveLevel = 0;      // physical level that means "field off"
  std::string pwmDutyPath;    // sysfs duty_cycle to zero (best effort)
  std::vector<std::string> warnings;
};

FieldOffPlan planFieldOff(const LoadResult& loaded);

}  // namespace xr
