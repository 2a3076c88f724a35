// PwmSysfs against a fake /sys/class/pwm tree (docs/install.md).
#include "drivers/pwm/pwm_sysfs.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "temp_dir.h"

namespace xr {
namespace {

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

class PwmSysfsTest : public ::testing::Test {
 protected:
  void makeChannel(int chip, int ch) {
    const std::string d = dir / ("pwmchip" + std::to_string(chip) + "/pwm" + std::to_string(ch));
    for (const char* f : {"period", "duty_cycle", "enable", "polarity"}) test::writeFile(d + "/" + f, "0\n");
  }
  std::string attr(const std::string& name) { return trim(test::readFile(dir / ("pwmchip0/pwm0/" + name))); }
  test::TempDir dir;
};

TEST_F(PwmSysfsTest, MissingChipNamesTheOverlay) {
  PwmSysfs pwm;
  EXPECT_FALSE(pwm.open(dir.path(), 0, 0, 400.0, false));
  EXPECT_NE(pwm.error().find("dtoverlay=pwm"), std::string::npos) << pwm.error();
  EXPECT_FALSE(pwm.isOpen());
  EXPECT_FALSE(pwm.setDutyPercent(50.0)) << "writes fail cleanly when not open";
  EXPECT_FALSE(pwm.setEnabled(true));
}

TEST_F(PwmSysfsTest, ConfiguresPeriodPolarityAndStartsDisabledAtZero) {
  makeChannel(0, 0);
  test::writeFile(dir / "pwmchip0/pwm0/duty_cycle", "1234567\n");
  test::writeFile(dir / "pwmchip0/pwm0/enable", "1\n");
  PwmSysfs pwm;
  ASSERT_TRUE(pwm.open(dir.path(), 0, 0, 400.0, true)) << pwm.error();
  EXPECT_EQ(attr("period"), "2500000");
  EXPECT_EQ(attr("polarity"), "inversed");
  EXPECT_EQ(attr("duty_cycle"), "0");
  EXPECT_EQ(attr("enable"), "0");
  EXPECT_EQ(pwm.periodNs(), 2'500'000);
}

TEST_F(PwmSysfsTest, DutyInNanosecondsAndEnable) {
  makeChannel(0, 0);
  PwmSysfs pwm;
  ASSERT_TRUE(pwm.open(dir.path(), 0, 0, 400.0, false)) << pwm.error();
  EXPECT_EQ(attr("polarity"), "normal");
  ASSERT_TRUE(pwm.setDutyPercent(37.5));
  EXPECT_EQ(attr("duty_cycle"), "937500");
  ASSERT_TRUE(pwm.setEnabled(true));
  EXPECT_EQ(attr("enable"), "1");
  ASSERT_TRUE(pwm.setDutyPercent(3.0));
  EXPECT_EQ(attr("duty_cycle"), "75000") << "a shorter value leaves no stale digits";
}

TEST_F(PwmSysfsTest, DutyIsClampedAndNanIsZero) {
  EXPECT_EQ(PwmSysfs::dutyNsFor(150.0, 1000), 1000);
  EXPECT_EQ(PwmSysfs::dutyNsFor(-5.0, 1000), 0);
  EXPECT_EQ(PwmSysfs::dutyNsFor(std::nan(""), 1000), 0);
  EXPECT_EQ(PwmSysfs::dutyNsFor(50.0, 2'500'000), 1'250'000);
}

TEST_F(PwmSysfsTest, ExportsTheChannelWhenNeeded) {
  test::writeFile(dir / "pwmchip0/export", "");
  PwmSysfs pwm;
  // The fake tree has no kernel behind it: the channel never appears, and
  // the error says so after writing the channel number to export.
  EXPECT_FALSE(pwm.open(dir.path(), 0, 1, 400.0, false));
  EXPECT_EQ(trim(test::readFile(dir / "pwmchip0/export")), "1");
  EXPECT_NE(pwm.error().find("did not appear"), std::string::npos) << pwm.error();
}

TEST_F(PwmSysfsTest, RejectsAbsurdFrequency) {
  makeChannel(0, 0);
  PwmSysfs pwm;
  EXPECT_FALSE(pwm.open(dir.path(), 0, 0, 0.0, false));
  EXPECT_FALSE(pwm.open(dir.path(), 0, 0, std::nan(""), false));
  EXPECT_FALSE(pwm.error().empty());
}

TEST_F(PwmSysfsTest, SafeStateWriterDrivesDutyAndEnableToZero) {
  makeChannel(0, 0);
  PwmSysfs pwm;
  ASSERT_TRUE(pwm.open(dir.path(), 0, 0, 400.0, false));
  pwm.setDutyPercent(80.0);
  pwm.setEnabled(true);
  const PwmSafeStateWriter w = pwm.safeStateWriter();
  ASSERT_GE(w.dutyFd, 0);
  ASSERT_GE(w.enableFd, 0);
  EXPECT_TRUE(w.driveSafe());
  EXPECT_EQ(attr("duty_cycle"), "0");
  EXPECT_EQ(attr("enable"), "0");
}

TEST_F(PwmSysfsTest, DestructorLeavesTheFieldOff) {
  makeChannel(0, 0);
  {
    PwmSysfs pwm;
    ASSERT_TRUE(pwm.open(dir.path(), 0, 0, 400.0, false));
    pwm.setDutyPercent(60.0);
    pwm.setEnabled(true);
  }
  EXPECT_EQ(attr("duty_cycle"), "0");
  EXPECT_EQ(attr("enable"), "0");
}

TEST(PwriteLong, FormatsWithoutSnprintf) {
  test::TempDir d;
  test::writeFile(d / "f", "");
  const int fd = ::open((d / "f").c_str(), O_WRONLY);
  ASSERT_GE(fd, 0);
  EXPECT_TRUE(pwriteLong(fd, -1234567, true));
  EXPECT_EQ(test::readFile(d / "f"), "-1234567\n");
  EXPECT_TRUE(pwriteLong(fd, 0, true));
  EXPECT_EQ(test::readFile(d / "f"), "0\n");
  ::close(fd);
  EXPECT_FALSE(pwriteLong(-1, 5));
}

}  // namespace
}  // namespace xr
