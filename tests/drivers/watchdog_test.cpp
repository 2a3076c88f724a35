// LinuxWatchdog with a temp file standing in for /dev/watchdog: keep-alive
// bytes, no 'V' unless closeClean(), ENOTTY tolerated and reported.
#include <gtest/gtest.h>

#include "drivers/watchdog/linux_watchdog.h"
#include "temp_dir.h"

namespace xr {
namespace {

TEST(LinuxWatchdog, MissingDeviceIsAClearError) {
  LinuxWatchdog wd;
  EXPECT_FALSE(wd.open("/nonexistent/watchdog", 10));
  EXPECT_NE(wd.error().find("dtparam=watchdog=on"), std::string::npos) << wd.error();
  EXPECT_FALSE(wd.keepAlive());
}

TEST(LinuxWatchdog, PlainFileIsAcceptedButReported) {
  test::TempDir d;
  test::writeFile(d / "wd", "");
  LinuxWatchdog wd;
  ASSERT_TRUE(wd.open(d / "wd", 10)) << wd.error();
  EXPECT_NE(wd.warning().find("WDIOC_SETTIMEOUT"), std::string::npos);
  EXPECT_EQ(wd.timeoutS(), 10);
}

TEST(LinuxWatchdog, KeepAliveWritesOneNonMagicBytePerCall) {
  test::TempDir d;
  test::writeFile(d / "wd", "");
  LinuxWatchdog wd;
  ASSERT_TRUE(wd.open(d / "wd", 10));
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(wd.keepAlive());
  EXPECT_EQ(wd.keepAlives(), 5u);
  const std::string s = test::readFile(d / "wd");
  EXPECT_EQ(s.size(), 5u);
  EXPECT_EQ(s.find('V'), std::string::npos);
}

TEST(LinuxWatchdog, MagicCloseOnlyOnCleanStop) {
  test::TempDir d;
  test::writeFile(d / "wd", "");
  {
    LinuxWatchdog wd;
    ASSERT_TRUE(wd.open(d / "wd", 10));
    wd.keepAlive();
    // destroyed without closeClean(): an unclean exit must leave it armed
  }
  EXPECT_EQ(test::readFile(d / "wd").find('V'), std::string::npos);
  LinuxWatchdog wd;
  ASSERT_TRUE(wd.open(d / "wd", 10));
  wd.keepAlive();
  wd.closeClean();
  const std::string s = test::readFile(d / "wd");
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(s.back(), 'V');
  EXPECT_FALSE(wd.isOpen());
  EXPECT_FALSE(wd.keepAlive()) << "no keep-alive after the magic close";
}

TEST(LinuxWatchdog, NoKeepAliveMeansNoBytes) {
  // A stalled loop does not call keepAlive(): nothing reaches the device.
  test::TempDir d;
  test::writeFile(d / "wd", "");
  LinuxWatchdog wd;
  ASSERT_TRUE(wd.open(d / "wd", 10));
  EXPECT_TRUE(test::readFile(d / "wd").empty());
}

TEST(LinuxWatchdog, RejectsZeroTimeout) {
  test::TempDir d;
  test::writeFile(d / "wd", "");
  LinuxWatchdog wd;
  EXPECT_FALSE(wd.open(d / "wd", 0));
}

}  // namespace
}  // namespace xr
