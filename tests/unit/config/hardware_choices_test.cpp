// The battery probe and BMS bus an owner picks on the set-up page
// (config/hardware_choices.h), and the file's battery probe id, which passes
// the same check (docs/configuration.md "Set-up").
#include "config/hardware_choices.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "config/config.h"

namespace xr {
namespace {

using ::testing::HasSubstr;

TEST(HardwareChoices, AOneWireIdIsFamilyDashTwelveHexDigits) {
  EXPECT_TRUE(isOneWireId("28-0316a2794aff"));
  EXPECT_TRUE(isOneWireId("10-0000ABCDEF01"));
  EXPECT_FALSE(isOneWireId("28-0316a2794af"));    // 11 digits
  EXPECT_FALSE(isOneWireId("28-0316a2794aff0"));  // 13
  EXPECT_FALSE(isOneWireId("28_0316a2794aff"));
  EXPECT_FALSE(isOneWireId("28-0316a2794afg"));
  EXPECT_FALSE(isOneWireId("../../etc/passwd"));
  EXPECT_FALSE(isOneWireId(""));
}

TEST(HardwareChoices, AChoiceLiesOverTheFileAndUnsetKeepsTheFiles) {
  Settings file;
  file.hardware.battery_temp_sensor = "28-000000000001";
  file.can.bms_interface = "can0";
  const Settings s = withHardwareChoices(file, {std::nullopt, std::string(""), 2.5});
  EXPECT_EQ(s.hardware.battery_temp_sensor, "28-000000000001");
  EXPECT_EQ(s.can.bms_interface, "") << "\"\" is none, whatever the file says";
  EXPECT_EQ(s.hardware.frontend.pulley_ratio, 2.5);
}

TEST(HardwareChoices, ANumberIsKeptAsExactText) {
  for (double v : {2.7, 0.01, 1.0 / 3.0, 100.0})
    EXPECT_EQ(parseChoiceNumber(choiceNumberText(v)), std::optional<double>(v));
  EXPECT_FALSE(parseChoiceNumber(std::string("2.5x")).has_value());
  EXPECT_FALSE(parseChoiceNumber(std::string("inf")).has_value());
  EXPECT_FALSE(parseChoiceNumber(std::string("")).has_value());
  EXPECT_FALSE(choiceNumberText(std::nullopt).has_value());
}

TEST(HardwareChoices, TheFilesBatteryProbeIsCheckedToo) {
  const auto bad = loadConfigString("[hardware]\nbattery_temp_sensor = \"28-abc\"\n", "test.toml");
  ASSERT_EQ(bad.errors.size(), 1u);
  EXPECT_THAT(bad.errors[0].toString(), HasSubstr("not a DS18B20 id"));
  const auto same = loadConfigString(
      "[hardware]\nonewire_sensor_id = \"28-000000000001\"\nbattery_temp_sensor = \"28-000000000001\"\n",
      "test.toml");
  ASSERT_EQ(same.errors.size(), 1u);
  EXPECT_THAT(same.errors[0].toString(), HasSubstr("alternator's sensor"));
  EXPECT_TRUE(
      loadConfigString("[hardware]\nbattery_temp_sensor = \"28-000000000002\"\n", "t").errors.empty());
}

TEST(HardwareChoices, AnUpperCaseCopyOfTheAlternatorsProbeIsRefusedAsTheBatterys) {
  HardwareSettings h;
  h.onewire_sensor_id = "28-0316a2794aff";
  h.battery_temp_sensor = "28-0316A2794AFF";  // the reproducer: accepted before
  auto e = checkBatteryProbe(h);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].first, "hardware.battery_temp_sensor");
  EXPECT_THAT(e[0].second, HasSubstr("alternator's sensor"));
  // Another probe in upper case is no id the kernel lists either.
  h.battery_temp_sensor = "28-0316A2794AF0";
  e = checkBatteryProbe(h);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_THAT(e[0].second, HasSubstr("lower case"));
  h.battery_temp_sensor = "28-0316a2794af0";
  EXPECT_TRUE(checkBatteryProbe(h).empty());
}

TEST(HardwareChoices, OnlyADs18b20FamilyIdIsTakenWhereTheDocsSay28) {
  EXPECT_TRUE(isDs18b20Id("28-0316a2794aff"));
  EXPECT_FALSE(isDs18b20Id("10-0316a2794aff"));  // a DS18S20: the reproducer
  EXPECT_FALSE(isDs18b20Id("3b-0316a2794aff"));
  HardwareSettings h;
  h.battery_temp_sensor = "10-0316a2794aff";
  auto e = checkBatteryProbe(h);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].first, "hardware.battery_temp_sensor");
  h = {};
  h.onewire_sensor_id = "10-0316a2794aff";
  e = checkBatteryProbe(h);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].first, "hardware.onewire_sensor_id");
}

TEST(HardwareChoices, TheNmea2000BusSentAsTheBmsBusIsFiledUnderTheBmsSetting) {
  Settings file;
  file.can.n2k_interface = "can1";
  const auto e = checkHardwareChoices(file, {std::nullopt, std::string("can1"), std::nullopt});
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].first, "can.bms_interface");  // before: can.n2k_interface, a setting not sent
  EXPECT_THAT(e[0].second, HasSubstr("NMEA 2000 bus"));
}

}  // namespace
}  // namespace xr
