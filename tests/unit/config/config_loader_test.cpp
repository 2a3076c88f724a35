#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "config/config.h"
#include "config/param_values.h"
#include "test_files.h"

namespace xr {
namespace {

using ::testing::HasSubstr;
using xr::testing::TempFile;

struct Checked {
  int code;
  std::string out;
  std::string err;
};

Checked check(std::string_view text) {
  TempFile f(text);
  std::ostringstream out, err;
  const int code = checkConfigMain(f.path(), out, err);
  return {code, out.str(), err.str()};
}

std::vector<std::string> messages(std::string_view text) {
  std::vector<std::string> m;
  for (const auto& e : loadConfigString(text, "test.toml").errors) m.push_back(e.toString());
  return m;
}

TEST(DefaultConfig, LoadsToExactlyTheBuiltInDefaults) {
  const LoadResult r = loadConfigString(defaultConfigText(), "default");
  ASSERT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors.front().toString());
  EXPECT_EQ(r.config->params, Params{});
  EXPECT_TRUE(overridesFromDefaults(r.config->params).empty());
  EXPECT_EQ(r.config->settings.hardware.i2c_bus, Settings{}.hardware.i2c_bus);
  EXPECT_EQ(r.config->settings.hardware.ina228_address, 0x40);
  EXPECT_EQ(r.config->settings.hardware.ads_channel_sequence, Settings{}.hardware.ads_channel_sequence);
  EXPECT_EQ(r.config->settings.web.port, Settings{}.web.port);
  EXPECT_EQ(r.config->settings.log.level, "info");
}

TEST(DefaultConfig, PrintedTextRoundTripsThroughCheckConfig) {
  const Checked c = check(defaultConfigText());
  EXPECT_EQ(c.code, 0) << c.err;
  EXPECT_THAT(c.out, HasSubstr(": OK"));
  EXPECT_THAT(c.out, HasSubstr("0 differ from the defaults"));
  EXPECT_TRUE(c.err.empty());
}

TEST(DefaultConfig, EmptyFileIsValidAndMeansDefaults) {
  const LoadResult r = loadConfigString("", "empty");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.config->params, Params{});
}

TEST(LoadConfig, ValuesLandInParamsAndSettings) {
  const LoadResult r = loadConfigString(R"(
[voltage]
BulkVoltage = 14.2
AbsorptionVoltage = 14.1
[charging]
UseFloat = false
[modes]
TargetVoltageMode = 1
[rpm_tables]
rpmCapCurrentTable = [0, 40, 40, 40, 40, 40, 40, 40, 40, 40]
[hardware]
i2c_bus = "/dev/i2c-3"
ina228_address = 0x41
[hardware.frontend]
hall_invert = true
[web]
port = 9000
[log]
level = "debug"
)",
                                        "t");
  ASSERT_TRUE(r.ok()) << r.errors.front().toString();
  const auto& c = *r.config;
  EXPECT_DOUBLE_EQ(c.params.BulkVoltage, 14.2);
  EXPECT_DOUBLE_EQ(c.params.AbsorptionVoltage, 14.1);
  EXPECT_FALSE(c.params.UseFloat);
  EXPECT_TRUE(c.params.TargetVoltageMode);
  EXPECT_DOUBLE_EQ(c.params.rpmCapCurrentTable[1], 40.0);
  EXPECT_EQ(c.settings.hardware.i2c_bus, "/dev/i2c-3");
  EXPECT_EQ(c.settings.hardware.ina228_address, 0x41);
  EXPECT_TRUE(c.settings.hardware.frontend.hall_invert);
  EXPECT_EQ(c.settings.web.port, 9000);
  EXPECT_EQ(c.settings.log.level, "debug");
}

TEST(BadConfig, SyntaxErrorNamesFileLineColumnAndExits78) {
  const auto m = messages("[voltage]\nBulkVoltage = 14.5\nFloatVoltage = = 13\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("test.toml:3:"));
  EXPECT_THAT(m[0], HasSubstr("TOML syntax error"));
  const Checked c = check("[voltage\nBulkVoltage = 14.5\n");
  EXPECT_EQ(c.code, kExitConfig);
  EXPECT_EQ(c.code, 78);
  EXPECT_THAT(c.err, HasSubstr(":1:"));
  EXPECT_THAT(c.err, HasSubstr("will not start"));
}

TEST(BadConfig, UnknownKeySuggestsClosestName) {
  const Checked c = check("[voltage]\nBulkVoltag = 14.5\n");
  EXPECT_EQ(c.code, 78);
  EXPECT_THAT(c.err, HasSubstr(":2:1: voltage.BulkVoltag: unknown parameter (did you mean BulkVoltage?)"));
}

TEST(BadConfig, UnknownKeyInTheWrongTableSuggestsNameAndTable) {
  const auto m = messages("[battery]\nfloatvoltage = 13.2\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("did you mean FloatVoltage, in [voltage]?"));
}

TEST(BadConfig, UnknownTableSuggestsClosestTable) {
  const auto m = messages("[voltag]\nBulkVoltage = 14.5\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("voltag: unknown table or key (did you mean voltage?)"));
}

TEST(BadConfig, UnknownSettingSuggestsClosestSetting) {
  const Checked c = check("[hardware]\ni2c_buss = \"/dev/i2c-1\"\n");
  EXPECT_EQ(c.code, 78);
  EXPECT_THAT(c.err, HasSubstr("hardware.i2c_buss: unknown setting (did you mean i2c_bus?)"));
}

TEST(BadConfig, ParameterInWrongTableSaysWhereItBelongs) {
  const auto m = messages("[battery]\nBulkVoltage = 14.5\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("BulkVoltage belongs in [voltage], not [battery]"));
  const auto top = messages("BulkVoltage = 14.5\n");
  ASSERT_EQ(top.size(), 1u);
  EXPECT_THAT(top[0], HasSubstr("put BulkVoltage under [voltage]"));
}

TEST(BadConfig, WrongTypeNamesKeyValueRangeAndUnit) {
  const Checked c = check("[voltage]\nBulkVoltage = \"high\"\n");
  EXPECT_EQ(c.code, 78);
  EXPECT_THAT(c.err, HasSubstr("voltage.BulkVoltage: expected a number (allowed 8 to 64 V), got string \"high\""));
}

TEST(BadConfig, OutOfRangeNamesKeyValueRangeAndUnit) {
  const Checked c = check("[voltage]\nBulkVoltage = 99\n");
  EXPECT_EQ(c.code, 78);
  EXPECT_THAT(c.err, HasSubstr(":2:1: voltage.BulkVoltage: 99 is out of range: allowed 8 to 64 V"));
}

TEST(BadConfig, FractionForWholeNumberParameterIsRejected) {
  const auto m = messages("[voltage]\nVoltageLoopInterval = 100.5\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("100.5 is not a whole number: allowed 10 to 5000 ms"));
}

TEST(BadConfig, SwitchAcceptsOnlyZeroOneOrBooleans) {
  EXPECT_TRUE(messages("[charging]\nUseFloat = 1\n").empty());
  EXPECT_TRUE(messages("[charging]\nUseFloat = true\n").empty());
  const auto m = messages("[charging]\nUseFloat = 2\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("charging.UseFloat: 2 is out of range: allowed 0 or 1"));
  EXPECT_THAT(messages("[charging]\nUseFloat = \"yes\"\n").at(0), HasSubstr("expected true/false or 0/1"));
}

TEST(BadConfig, TableNeedsTenNumbersInRange) {
  EXPECT_THAT(messages("[rpm_tables]\nrpmMinDutyTable = [5, 5, 4]\n").at(0),
              HasSubstr("rpm_tables.rpmMinDutyTable: expected 10 values, got 3"));
  EXPECT_THAT(messages("[rpm_tables]\nrpmMinDutyTable = [5, 5, 4, 4, 3, 300, 2, 2, 1, 1]\n").at(0),
              HasSubstr("element 5 = 300 is out of range: allowed 0 to 100 %"));
  EXPECT_THAT(messages("[rpm_tables]\nrpmMinDutyTable = 5\n").at(0), HasSubstr("expected a list of 10 numbers"));
}

TEST(BadConfig, SettingTypeRangeAndChoices) {
  EXPECT_THAT(messages("[web]\nport = 70000\n").at(0), HasSubstr("web.port: 70000 is out of range: allowed 1 to 65535"));
  EXPECT_THAT(messages("[web]\nport = \"80\"\n").at(0), HasSubstr("web.port: expected a whole number"));
  EXPECT_THAT(messages("[log]\nlevel = \"loud\"\n").at(0),
              HasSubstr("log.level: \"loud\" is not one of: trace,debug,info,warn,error,critical,off"));
  EXPECT_THAT(messages("[hardware]\nads_channel_sequence = [1, 7]\n").at(0),
              HasSubstr("element 7 is out of range: allowed 0 to 3"));
  EXPECT_THAT(messages("[hardware.frontend]\nhall_zero_v = 9\n").at(0),
              HasSubstr("hardware.frontend.hall_zero_v: 9 is out of range: allowed 0 to 5 V"));
}

TEST(BadConfig, EveryErrorOfTheFileIsReportedInFileOrder) {
  const Checked c = check(R"([voltage]
BulkVoltage = 99
FloatVoltag = 13.2
[temperature]
TemperatureLimitF = "hot"
[web]
port = 0
)");
  EXPECT_EQ(c.code, 78);
  const auto m = messages(R"([voltage]
BulkVoltage = 99
FloatVoltag = 13.2
[temperature]
TemperatureLimitF = "hot"
[web]
port = 0
)");
  ASSERT_EQ(m.size(), 4u);
  EXPECT_THAT(m[0], HasSubstr(":2:1: voltage.BulkVoltage"));
  EXPECT_THAT(m[1], HasSubstr(":3:1: voltage.FloatVoltag"));
  EXPECT_THAT(m[2], HasSubstr(":5:1: temperature.TemperatureLimitF"));
  EXPECT_THAT(m[3], HasSubstr(":7:1: web.port"));
  EXPECT_THAT(c.err, HasSubstr("4 errors"));
}

TEST(BadConfig, InconsistentVoltagesAreRejectedAtTheirLine) {
  const auto m = messages("[voltage]\nBulkVoltage = 14.4\nAbsorptionVoltage = 14.6\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr(":3:1: voltage.AbsorptionVoltage: 14.6 V is above BulkVoltage 14.4 V"));
}

TEST(BadConfig, HardShutdownBelowBulkIsRejected) {
  const auto m = messages("[voltage]\nAlternatorHardShutdownV = 14.0\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("must be above BulkVoltage 14.5 V"));
  EXPECT_TRUE(messages("[voltage]\nAlternatorHardShutdownV = 14.8\n").empty());
}

TEST(BadConfig, FieldEnableLineCannotBeShared) {
  const auto m = messages("[hardware]\nfield_enable_line = 21\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("hardware.buzzer_line: uses GPIO line 21, which is already the field_enable_line"));
}

TEST(BadConfig, MissingFileIsAnErrorWithExit78) {
  std::ostringstream out, err;
  EXPECT_EQ(checkConfigMain("/nonexistent/xregulator.toml", out, err), 78);
  EXPECT_THAT(err.str(), HasSubstr("/nonexistent/xregulator.toml: cannot read the file"));
}

TEST(Consistency, DefaultsAreConsistent) { EXPECT_TRUE(checkConsistency(Params{}).empty()); }

TEST(Consistency, CatchesEachCrossParameterRule) {
  auto firstKey = [](const Params& p) {
    auto e = checkConsistency(p);
    return e.empty() ? std::string("none") : e.front().key;
  };
  Params p;
  p.FloatVoltage = 14.45;
  EXPECT_EQ(firstKey(p), "voltage.FloatVoltage");
  p = {};
  p.RebulkVoltage = 13.5;
  EXPECT_EQ(firstKey(p), "voltage.RebulkVoltage");
  p = {};
  p.TargetVoltageSetpoint = 14.9;
  EXPECT_EQ(firstKey(p), "voltage.TargetVoltageSetpoint");
  p = {};
  p.MinDuty = 50;
  p.MaxDuty = 40;
  EXPECT_EQ(firstKey(p), "tuning.MinDuty");
  p = {};
  p.VoltageAlarmLow = 15.5;
  EXPECT_EQ(firstKey(p), "alarms.VoltageAlarmLow");
  p = {};
  p.TempWarnExcess = 20;
  EXPECT_EQ(firstKey(p), "temperature.TempWarnExcess");
  p = {};
  p.SOC_AllowRebulk_percent = 99;
  EXPECT_EQ(firstKey(p), "charging.SOC_AllowRebulk_percent");
  p = {};
  p.LoadDumpDtThresh3 = 5000;
  EXPECT_EQ(firstKey(p), "overvoltage.LoadDumpDtThresh");
  p = {};
  p.rpmTableRPMPoints[4] = p.rpmTableRPMPoints[3];
  EXPECT_EQ(firstKey(p), "rpm_tables.rpmTableRPMPoints");
}

}  // namespace
}  // namespace xr
