// GpioLibgpiod: polarity logic and the error paths (no gpiochip on the CI box).
#include <gtest/gtest.h>

#include "drivers/gpio/gpio_libgpiod.h"

namespace xr {
namespace {

TEST(GpioPolarity, PhysicalLevelForActiveHighAndLow) {
  EXPECT_EQ(physicalLevel(true, true), 1);
  EXPECT_EQ(physicalLevel(false, true), 0);
  EXPECT_EQ(physicalLevel(true, false), 0);
  EXPECT_EQ(physicalLevel(false, false), 1) << "an active-low enable idles HIGH (off)";
}

TEST(GpioPolarity, LogicalLevelFromPhysical) {
  EXPECT_EQ(logicalLevel(1, false), 1);
  EXPECT_EQ(logicalLevel(0, false), 0);
  EXPECT_EQ(logicalLevel(1, true), 0);
  EXPECT_EQ(logicalLevel(0, true), 1);
  EXPECT_EQ(logicalLevel(-1, true), -1) << "errors stay errors";
}

TEST(GpioLibgpiod, MissingChipIsAClearErrorAndNothingIsRequested) {
  HardwareSettings hw;
  hw.gpio_chip = "gpiochip-does-not-exist";
  GpioLibgpiod g;
  EXPECT_FALSE(g.open(hw));
  EXPECT_NE(g.error().find("gpiochip-does-not-exist"), std::string::npos) << g.error();
  EXPECT_EQ(g.fieldEnable(), nullptr);
  EXPECT_EQ(g.buzzer(), nullptr);
  EXPECT_EQ(g.bms(), nullptr);
  EXPECT_EQ(g.ignition(), nullptr);
}

TEST(GpioLibgpiod, NullLinesFailSafely) {
  GpioOutputLine out(nullptr, true);
  EXPECT_FALSE(out.set(true));
  GpioInputLine in(nullptr, false);
  EXPECT_EQ(in.get(), -1);
}

TEST(AdsReadyLine, MissingChipIsAnError) {
  AdsReadyLine l;
  EXPECT_FALSE(l.open("gpiochip-does-not-exist", 17));
  EXPECT_FALSE(l.error().empty());
  long long ts = 0;
  EXPECT_EQ(l.wait(1000, &ts), -1);
  EXPECT_EQ(l.fd(), -1);
}

}  // namespace
}  // namespace xr

namespace xr {
namespace {

TEST(GpioOutputLine, SignalSafeOffToleratesNull) {
  GpioOutputLine out(nullptr, true);
  GpioOutputLine::setOffSignalSafe(&out);  // no line: nothing to do, no crash
  GpioOutputLine::setOffSignalSafe(nullptr);
  EXPECT_FALSE(out.set(false));
}

}  // namespace
}  // namespace xr
