// OperatorCommands on its own (docs/operations.md "Commands"): a manual duty
// at 100 % holds, just over it is refused and the last command stands;
// automatic clears manual and off; other parts' commands are not its own.
#include "control/operator_commands.h"

#include <gtest/gtest.h>

#include <limits>

namespace xr {
namespace {

Command manual(double duty) {
  Command c;
  c.type = CommandType::Manual;
  c.value = duty;
  return c;
}

TEST(OperatorCommandsPart, ManualAtTheLimitHoldsJustOverIsRefused) {
  Params p;
  OperatorCommands ops;
  EXPECT_EQ(ops.apply(manual(100.0)), std::optional<bool>(true));
  EXPECT_TRUE(ops.manualMode(p));
  EXPECT_DOUBLE_EQ(ops.manualDuty(p), 100.0);
  EXPECT_EQ(ops.apply(manual(100.01)), std::optional<bool>(false));
  EXPECT_EQ(ops.apply(manual(-0.01)), std::optional<bool>(false));
  EXPECT_EQ(ops.apply(manual(std::numeric_limits<double>::quiet_NaN())), std::optional<bool>(false));
  EXPECT_DOUBLE_EQ(ops.manualDuty(p), 100.0);  // the last legal command stands
}

TEST(OperatorCommandsPart, AutoClearsManualAndOff) {
  Params p;
  p.ManualDutyTarget = 33.0;
  OperatorCommands ops;
  ops.apply(manual(40.0));
  Command off;
  off.type = CommandType::Off;
  ops.apply(off);
  EXPECT_TRUE(ops.off());
  Command autoCmd;
  autoCmd.type = CommandType::Auto;
  ops.apply(autoCmd);
  EXPECT_FALSE(ops.off());
  EXPECT_FALSE(ops.manualMode(p));
  EXPECT_DOUBLE_EQ(ops.manualDuty(p), 33.0);  // ManualMode from the parameters drives ManualDutyTarget
  p.ManualMode = true;
  EXPECT_TRUE(ops.manualMode(p));
}

TEST(OperatorCommandsPart, LimpHomeAndWeatherAreItsOwnTheRestAreNot) {
  OperatorCommands ops;
  Command c;
  c.type = CommandType::LimpHome;
  ops.apply(c);
  EXPECT_TRUE(ops.limpHome());
  c.type = CommandType::LimpHomeOff;
  ops.apply(c);
  EXPECT_FALSE(ops.limpHome());
  c.type = CommandType::WeatherMode;
  c.flag = true;
  ops.apply(c);
  EXPECT_TRUE(ops.weatherMode());
  c.type = CommandType::ResetAlarmLatch;
  EXPECT_FALSE(ops.apply(c).has_value());
}

}  // namespace
}  // namespace xr
