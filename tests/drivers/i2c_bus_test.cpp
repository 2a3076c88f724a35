// LinuxI2cBus error paths (docs/install.md): no device, a file that is not an
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

#include <fcntl.h>

namespace xr {
namespace {

TEST(LinuxI2cBus, IoctlErrorOnANonAdapterFdIsReturnedNotRetried) {
  LinuxI2cBus bus(/*retries=*/3);
  bus.adoptFd(::open("/dev/null", O_RDWR));
  ASSERT_TRUE(bus.isOpen());
  std::uint8_t ptr = 0x3E, buf[2] = {};
  I2cMsg msgs[2] = {{0x40, false, &ptr, 1}, {0x40, true, buf, 2}};
  EXPECT_EQ(bus.transfer(msgs), ENOTTY);
  EXPECT_EQ(bus.transfers(), 1u);
  EXPECT_EQ(bus.failures(), 1u);
  EXPECT_EQ(bus.retriesUsed(), 0u) << "ENOTTY is not transient";
}

TEST(LinuxI2cBus, BadMessageListsAreEinval) {
  LinuxI2cBus bus;
  bus.adoptFd(::open("/dev/null", O_RDWR));
  EXPECT_EQ(bus.transfer({}), EINVAL);
  I2cMsg many[LinuxI2cBus::kMaxMsgs + 1] = {};
  std::uint8_t b = 0;
  for (auto& m : many) m = {0x40, false, &b, 1};
  EXPECT_EQ(bus.transfer(many), EINVAL);
  I2cMsg nullBuf{0x40, true, nullptr, 2};
  EXPECT_EQ(bus.transfer({&nullBuf, 1}), EINVAL);
}

}  // namespace
}  // namespace xr
