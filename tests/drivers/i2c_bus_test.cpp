// LinuxI2cBus error paths (issue 7 tests): no device, a file that is not an
// i2c-dev adapter, transfers while closed or with bad message lists.
#include <gtest/gtest.h>

#include <cerrno>

#include "drivers/i2c/linux_i2c_bus.h"
#include "temp_dir.h"

namespace xr {
namespace {

TEST(LinuxI2cBus, NonexistentDeviceGivesEnoent) {
  LinuxI2cBus bus;
  EXPECT_EQ(bus.open("/dev/i2c-does-not-exist-77"), ENOENT);
  EXPECT_FALSE(bus.isOpen());
}

TEST(LinuxI2cBus, RegularFileIsRejectedByTheIoctl) {
  test::TempDir dir;
  test::writeFile(dir / "not-i2c", "hello");
  LinuxI2cBus bus;
  EXPECT_EQ(bus.open(dir / "not-i2c"), ENOTTY);
  EXPECT_FALSE(bus.isOpen());
}

TEST(LinuxI2cBus, DevNullIsNotAnAdapter) {
  LinuxI2cBus bus;
  const int rc = bus.open("/dev/null");
  EXPECT_NE(rc, 0);
  EXPECT_FALSE(bus.isOpen());
}

TEST(LinuxI2cBus, TransferWhileClosedIsEbadfNotACrash) {
  LinuxI2cBus bus;
  std::uint8_t b[2] = {};
  I2cMsg m{0x40, true, b, 2};
  EXPECT_EQ(bus.transfer({&m, 1}), EBADF);
}

TEST(LinuxI2cBus, TransientErrorClassification) {
  EXPECT_TRUE(isTransientI2cError(EREMOTEIO));
  EXPECT_TRUE(isTransientI2cError(ETIMEDOUT));
  EXPECT_TRUE(isTransientI2cError(EAGAIN));
  EXPECT_FALSE(isTransientI2cError(EBADF));
  EXPECT_FALSE(isTransientI2cError(ENOTTY));
  EXPECT_FALSE(isTransientI2cError(EINVAL));
}

}  // namespace
}  // namespace xr
