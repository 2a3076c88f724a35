// runProbe on fake trees: what it reports and its exit status.
#include "drivers/probe/probe.h"

#include <gtest/gtest.h>

#include <sstream>

#include "drivers/sim/ads1115_model.h"
#include "drivers/sim/ina228_model.h"
#include "sim_fixture.h"
#include "temp_dir.h"

namespace xr {
namespace {

class ProbeTest : public ::testing::Test {
 protected:
  ProbeTest() : bus(&t.now) {
    auto& hw = s.hardware;
    hw.i2c_bus = d / "no-i2c-1";
    hw.pwm_sysfs_root = d / "pwm";
    hw.gpio_chip = "gpiochip-does-not-exist";
    hw.watchdog_device = d / "watchdog";
    hw.w1_root = d / "w1";
  }
  std::string run(int* rc, I2cBus* b = nullptr) {
    std::ostringstream out;
    *rc = runProbe(s, out, b);
    return out.str();
  }
  test::TempDir d;
  Settings s;
  test::VirtualTime t;
  sim::SimI2cBus bus;
};

TEST_F(ProbeTest, MissingI2cTellsHowToEnableIt) {
  int rc = 0;
  const std::string out = run(&rc);
  EXPECT_EQ(rc, 1);
  EXPECT_NE(out.find("dtparam=i2c_arm=on"), std::string::npos) << out;
  EXPECT_NE(out.find("dtoverlay=pwm"), std::string::npos) << out;
  EXPECT_NE(out.find("dtoverlay=w1-gpio"), std::string::npos) << out;
  EXPECT_NE(out.find("dtparam=watchdog=on"), std::string::npos) << out;
  EXPECT_NE(out.find("[FAIL]"), std::string::npos);
}

TEST_F(ProbeTest, FindsBothChipsByIdOnTheBus) {
  sim::Ina228Model ina;
  sim::Ads1115Model ads;
  bus.attach(0x40, &ina);
  bus.attach(0x48, &ads);
  int rc = 0;
  const std::string out = run(&rc, &bus);
  EXPECT_NE(out.find("[ OK ] INA228 at 0x40 (MANUFACTURER_ID 0x5449"), std::string::npos) << out;
  EXPECT_NE(out.find("[ OK ] ADS1115 at 0x48"), std::string::npos) << out;
  EXPECT_EQ(ina.protocolErrors(), 0u);
  EXPECT_EQ(ads.protocolErrors(), 0u);
}

TEST_F(ProbeTest, MissingChipIsAFailure) {
  sim::Ads1115Model ads;
  bus.attach(0x48, &ads);
  int rc = 0;
  const std::string out = run(&rc, &bus);
  EXPECT_EQ(rc, 1);
  EXPECT_NE(out.find("[FAIL] INA228 at 0x40"), std::string::npos) << out;
}

TEST_F(ProbeTest, FakeTreesReportPwmWatchdogOneWireAndSerial) {
  test::writeFile(d / "pwm/pwmchip0/export", "");
  test::writeFile(d / "watchdog", "");
  test::writeFile(d / "w1/28-000001/w1_slave",
                  "2c 01 ff ff 7f ff ff ff 61 : crc=61 YES\n2c 01 ff ff 7f ff ff ff 61 t=18750\n");
  s.hardware.vedirect_port = "/dev/null";
  int rc = 0;
  const std::string out = run(&rc);
  EXPECT_NE(out.find("[ OK ] PWM"), std::string::npos) << out;
  EXPECT_NE(out.find("[ OK ] watchdog"), std::string::npos) << out;
  EXPECT_NE(out.find("[ OK ] 1-Wire 28-000001: 65.75"), std::string::npos) << out;
  EXPECT_NE(out.find("[FAIL] VE.Direct port /dev/null is not a serial port"), std::string::npos) << out;
  EXPECT_EQ(rc, 1);
}

TEST_F(ProbeTest, ConfiguredSensorMissingIsAFailure) {
  s.hardware.onewire_sensor_id = "28-deadbeef";
  int rc = 0;
  const std::string out = run(&rc);
  EXPECT_NE(out.find("28-deadbeef (configured) not present"), std::string::npos) << out;
}

}  // namespace
}  // namespace xr

namespace xr {
namespace {

TEST(ProbeI2cClock, ReadsTheBigEndianDeviceTreeValue) {
  test::TempDir d;
  const std::string dir = d / "class/i2c-dev/i2c-1/device/of_node";
  test::writeFile(dir + "/clock-frequency", std::string("\x00\x01\x86\xa0", 4));  // 100000
  EXPECT_EQ(readI2cClockHz("/dev/i2c-1", d.path()), 100000u);
  test::writeFile(dir + "/clock-frequency", std::string("\x00\x06\x1a\x80", 4));  // 400000
  EXPECT_EQ(readI2cClockHz("/dev/i2c-1", d.path()), 400000u);
  EXPECT_EQ(readI2cClockHz("/dev/i2c-7", d.path()), 0u);
  test::writeFile(dir + "/clock-frequency", "ab");
  EXPECT_EQ(readI2cClockHz("/dev/i2c-1", d.path()), 0u) << "short file";
}

}  // namespace
}  // namespace xr
