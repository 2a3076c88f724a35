// The checks on a whole parameter set (docs/configuration.md "Checks on the
// whole set"): each value in its range, but together for the wrong bank,
// unregulated, or alarming in normal operation. At each rule's edge, and
// through the configuration file as --check-config reads it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "config/config.h"
#include "params/derived.h"

namespace xr {
namespace {

using ::testing::HasSubstr;

std::vector<std::string> keys(const Params& p) {
  std::vector<std::string> k;
  for (const auto& e : checkConsistency(p)) k.push_back(e.key);
  return k;
}
std::string messages(const Params& p) {
  std::string m;
  for (const auto& e : checkConsistency(p)) m += e.message + "\n";
  return m;
}

TEST(BankClass, OneRuleSplitsAt18And36Volts) {
  EXPECT_EQ(bankClassOfVoltage(17.99), SystemClass::V12);
  EXPECT_EQ(bankClassOfVoltage(18.0), SystemClass::V24);
  EXPECT_EQ(bankClassOfVoltage(16.5), SystemClass::V12);  // a 12 V bank equalising
  EXPECT_EQ(bankClassOfVoltage(36.0), SystemClass::V24);
  EXPECT_EQ(bankClassOfVoltage(32.4), SystemClass::V24);  // a 24 V bank equalising
  EXPECT_EQ(bankClassOfVoltage(36.01), SystemClass::V48);
  Params p;
  p.BulkVoltage = 28.8;
  EXPECT_EQ(systemClass(p), SystemClass::V24);
}

TEST(SetChecks, A24VoltValueAmong12VoltOnesIsRefusedNamingBoth) {
  Params p;
  p.FloatVoltage = 27.0;  // the rest of the set is for 12 V
  EXPECT_THAT(keys(p), ::testing::Contains("voltage.FloatVoltage"));
  EXPECT_THAT(messages(p),
              HasSubstr("FloatVoltage 27 V is for a 24 V bank; BulkVoltage 14.5 V makes this a 12 V bank"));
}

TEST(SetChecks, AHighVoltageAlarmForAnotherBankIsRefused) {
  Params p;
  p.VoltageAlarmHigh = 40.0;
  EXPECT_THAT(keys(p), ::testing::Contains("alarms.VoltageAlarmHigh"));
  EXPECT_THAT(messages(p), HasSubstr("40 V is for a 48 V bank"));
}

TEST(SetChecks, AWhole24VoltSetIsConsistent) {
  Params p;
  p.BulkVoltage = 28.8;
  p.AbsorptionVoltage = 28.6;
  p.FloatVoltage = 27.0;
  p.RebulkVoltage = 25.8;
  p.TargetVoltageSetpoint = 27.2;
  p.ChargedVoltage = 27.6;
  p.VoltageAlarmHigh = 30.0;
  p.VoltageAlarmLow = 22.0;
  EXPECT_EQ(messages(p), "");
}

TEST(SetChecks, MinDutyMustStayBelowMaxDutyAndUnderHalfField) {
  Params p;
  p.MinDuty = 100;
  p.MaxDuty = 100;
  EXPECT_THAT(messages(p), HasSubstr("MinDuty 100 % must be below MaxDuty 100 %"));
  p.MaxDuty = 99;
  p.MinDuty = 50;  // the edge: allowed
  EXPECT_EQ(messages(p), "");
  p.MinDuty = 50.5;
  EXPECT_THAT(keys(p), ::testing::ElementsAre("tuning.MinDuty"));
}

TEST(SetChecks, AnAlarmInsideWhatTheRegulatorMayDoIsRefused) {
  Params p;
  p.VoltageAlarmHigh = p.BulkVoltage;  // at the target: sounds in every bulk charge
  EXPECT_THAT(keys(p), ::testing::ElementsAre("alarms.VoltageAlarmHigh"));
  p = {};
  p.TempAlarm = p.TemperatureLimitF;  // at the thermal limit the regulator holds
  EXPECT_THAT(keys(p), ::testing::ElementsAre("temperature.TempAlarm"));
  p.TempAlarm = p.TemperatureLimitF + 0.5;
  EXPECT_EQ(messages(p), "");
}

TEST(SetChecks, TheTemperatureCutMayNotLieBeyondClassHInsulation) {
  Params p;
  p.TemperatureLimitF = 400;
  p.TempAlarm = 100;
  const std::string m = messages(p);
  EXPECT_THAT(m, HasSubstr("TempAlarm"));
  EXPECT_THAT(m, HasSubstr("is above 356 °F (180 °C), the class H insulation limit"));
  p = {};
  p.TemperatureLimitF = 346;  // + TempCritExcess 10 = 356: the edge
  p.TempAlarm = 350;
  EXPECT_EQ(messages(p), "");
  p.TemperatureLimitF = 346.5;
  EXPECT_THAT(keys(p), ::testing::ElementsAre("temperature.TemperatureLimitF"));
}

TEST(SetChecks, TheFileIsRefusedAsPatchWouldRefuseIt) {
  // What --check-config reads: a 24 V charge set with a 12 V alarm written.
  const LoadResult r = loadConfigString(
      "[voltage]\nBulkVoltage = 28.8\nAbsorptionVoltage = 28.6\nFloatVoltage = 27.0\nRebulkVoltage = 25.8\n"
      "TargetVoltageSetpoint = 27.2\n[battery]\nChargedVoltage = 27.6\n[alarms]\nVoltageAlarmHigh = 15.0\n",
      "boat.toml");
  ASSERT_FALSE(r.ok());
  std::string all;
  for (const auto& e : r.errors) all += e.toString() + "\n";
  EXPECT_THAT(all, HasSubstr("alarms.VoltageAlarmHigh"));
  EXPECT_THAT(
      all, HasSubstr("VoltageAlarmHigh 15 V is for a 12 V bank; BulkVoltage 28.8 V makes this a 24 V bank"));
}

// The shipped file with one line uncommented and changed, as an installer
// edits it.
std::string shippedWith(const std::vector<std::pair<std::string, std::string>>& lines) {
  std::string text(defaultConfigText());
  for (const auto& [commented, written] : lines) {
    const auto at = text.find("\n" + commented + "\n");
    if (at == std::string::npos)
      ADD_FAILURE() << "not in the shipped file: " << commented;
    else
      text.replace(at + 1, commented.size(), written);
  }
  return text;
}

std::string allErrors(const LoadResult& r) {
  std::string all;
  for (const auto& e : r.errors) all += e.toString() + "\n";
  return all;
}

TEST(ShippedFile, ThreeHandWritten24VoltChargeVoltagesPass) {
  const LoadResult r =
      loadConfigString(shippedWith({{"# BulkVoltage = 14.5", "BulkVoltage = 28.8"},
                                    {"# AbsorptionVoltage = 14.4", "AbsorptionVoltage = 28.8"},
                                    {"# FloatVoltage = 13.5", "FloatVoltage = 27.0"}}),
                       "xregulator.toml");
  ASSERT_TRUE(r.ok()) << allErrors(r);
  const Params& p = r.config->params;
  EXPECT_DOUBLE_EQ(voltageAlarmHighV(p), 30.0);  // the bank's, not the 12 V default
  EXPECT_DOUBLE_EQ(rebulkVoltageV(p), 25.8);
}

TEST(ShippedFile, ARaisedAlternatorLimitPassesAndTheAlarmFollowsIt) {
  const LoadResult r = loadConfigString(
      shippedWith({{"# TemperatureLimitF = 150.0", "TemperatureLimitF = 200"}}), "xregulator.toml");
  ASSERT_TRUE(r.ok()) << allErrors(r);
  EXPECT_DOUBLE_EQ(tempAlarmF(r.config->params), 240.0);
  EXPECT_TRUE(r.config->notices.empty());
}

// An installed file from before the alarm followed the limit wrote
// TempAlarm = 190 beside it: raising the limit must not stop the next start.
TEST(ShippedFile, AnOlderFileWithTempAlarmWrittenKeepsStartingWithANotice) {
  const LoadResult r =
      loadConfigString("[temperature]\nTemperatureLimitF = 200\nTempAlarm = 190.0\n", "old.toml");
  ASSERT_TRUE(r.ok()) << allErrors(r);
  EXPECT_DOUBLE_EQ(tempAlarmF(r.config->params), 240.0);
  ASSERT_EQ(r.config->notices.size(), 1u);
  EXPECT_THAT(r.config->notices[0], HasSubstr("the alarm follows the limit at 240 degF"));
  // Just above the limit it is a valid alarm, used as written.
  const LoadResult kept =
      loadConfigString("[temperature]\nTemperatureLimitF = 200\nTempAlarm = 200.5\n", "old.toml");
  ASSERT_TRUE(kept.ok()) << allErrors(kept);
  EXPECT_DOUBLE_EQ(tempAlarmF(kept.config->params), 200.5);
  EXPECT_TRUE(kept.config->notices.empty());
}

// The set-up page's 90 degC: the refusal it used to meet named a field not on
// the page, in degF, twice.
TEST(SetChecks, NinetyDegreesCelsiusFromTheSetUpPagePasses) {
  Params p;
  p.TemperatureLimitF = 194.0;
  EXPECT_EQ(messages(p), "");
  p.TempAlarm = 190.0;  // a value the owner wrote on the Settings page: named there, in degC first
  EXPECT_THAT(messages(p),
              HasSubstr("the alternator temperature alarm (TempAlarm) 87.8 \u00B0C (190 \u00B0F) must be "
                        "above the alternator temperature limit 90 \u00B0C (194 \u00B0F)"));
}

// A current alarm at the cap sounds through every normal charge held there.
TEST(SetChecks, ACurrentAlarmAtTheCapIsRefusedNamingBoth) {
  Params p;
  p.MaxTableValue = 120;
  for (std::size_t i = 1; i < RPM_TABLE_SIZE; ++i) p.rpmCapCurrentTable[i] = 100;
  p.CurrentAlarmHigh = 100;  // the reproducer: 19 alarms in 10 minutes at the cap
  EXPECT_THAT(keys(p), ::testing::ElementsAre("current.CurrentAlarmHigh"));
  EXPECT_THAT(messages(p), HasSubstr("CurrentAlarmHigh 100 A must be at least 5 % above"));
  EXPECT_THAT(messages(p), HasSubstr("100 A (MaxTableValue and the RPM cap tables): at least 105 A"));
  p.CurrentAlarmHigh = 104.9;
  EXPECT_FALSE(messages(p).empty());
  p.CurrentAlarmHigh = 105;  // the edge
  EXPECT_EQ(messages(p), "");
  // The rating clips the table: a 60 A alternator under a 100 A table.
  p.MaxTableValue = 60;
  p.CurrentAlarmHigh = 63;
  EXPECT_EQ(messages(p), "");
  // The power cap can reach the rating.
  p.capLimitMode = 1;
  p.MaxTableValue = 120;
  p.CurrentAlarmHigh = 125;
  EXPECT_THAT(keys(p), ::testing::ElementsAre("current.CurrentAlarmHigh"));
}

}  // namespace
}  // namespace xr
