#include "field_off_plan.h"

namespace xr {

FieldOffPlan planFieldOff(const LoadResult& loaded) {
  FieldOffPlan plan;
  Settings s;
  if (loaded.ok()) {
    s = loaded.config->settings;
  } else {
    plan.warnings.push_back("configuration not usable; cutting the default field enable line instead");
    for (const auto& e : loaded.errors) plan.warnings.push_back(e.toString());
  }
  const auto& h = s.hardware;
  plan.gpioChip = h.gpio_chip;
  plan.enableLine = h.field_enable_line;
  plan.inactiveLevel = h.field_enable_active_high ? 0 : 1;
  plan.pwmDutyPath = h.pwm_sysfs_root + "/pwmchip" + std::to_string(h.pwm_chip) + "/pwm" +
                     std::to_string(h.pwm_channel) + "/duty_cycle";
  return plan;
}

}  // namespace xr
