#include <gtest/gtest.h>

#include "field_off_plan.h"

namespace xr {
namespace {

TEST(FieldOffPlan, UsesTheConfiguredLineAndPolarity) {
  const auto plan = planFieldOff(loadConfigString(R"(
[hardware]
gpio_chip = "gpiochip4"
field_enable_line = 17
field_enable_active_high = false
pwm_chip = 2
pwm_channel = 1
)",
                                                  "t"));
  EXPECT_TRUE(plan.warnings.empty());
  EXPECT_EQ(plan.gpioChip, "gpiochip4");
  EXPECT_EQ(plan.enableLine, 17);
  EXPECT_EQ(plan.inactiveLevel, 1);  // active-low enable: HIGH is off
  EXPECT_EQ(plan.pwmDutyPath, "/sys/class/pwm/pwmchip2/pwm1/duty_cycle");
}

TEST(FieldOffPlan, ActiveHighEnableIsCutByDrivingLow) {
  const auto plan = planFieldOff(loadConfigString("", "t"));
  EXPECT_EQ(plan.enableLine, 4);
  EXPECT_EQ(plan.inactiveLevel, 0);
}

TEST(FieldOffPlan, BrokenConfigStillCutsTheDefaultLineAndSaysWhy) {
  const auto plan = planFieldOff(loadConfigString("[hardware]\nfield_enable_line = \"four\"\n", "bad.toml"));
  EXPECT_EQ(plan.gpioChip, "gpiochip0");
  EXPECT_EQ(plan.enableLine, 4);
  EXPECT_EQ(plan.inactiveLevel, 0);
  ASSERT_GE(plan.warnings.size(), 2u);
  EXPECT_NE(plan.warnings[1].find("bad.toml:2:1"), std::string::npos);
}

}  // namespace
}  // namespace xr
