// Battery profiles (docs/batteries.md): each profile's effective values at 12, 24 and
// 48 V against the published figures (docs/sources.md P3.6-3.8), overrides,
// provenance, and the profile limits that refuse a file.
#include "config/battery_profiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "config/config.h"
#include "config/param_sources.h"
#include "params/derived.h"

namespace xr {
namespace {

Config load(const std::string& text) {
  const LoadResult r = loadConfigString(text, "test.toml");
  EXPECT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors.front().toString());
  return r.config.value_or(Config{});
}

std::vector<ConfigError> errorsOf(const std::string& text) {
  return loadConfigString(text, "test.toml").errors;
}

// The published 12 V value at 25 degC of each profile, and its source
// (docs/sources.md P3.6-3.8): absorption, float, rebulk, tail as % of C, absorption
// hours, C-rate, mV/degC/cell, min / full-current / max charge degC.
struct Row {
  const char* profile;
  int cells12;
  double absorption12, float12, rebulk12;
  bool useFloat;
  double tailFraction, hours, rateC, compMv, minC, fullC, maxC;
  bool tempRequired;
};
const Row kRows[] = {
    // VIC-CHG Li-ion 14.2 / 13.5 V; TAR #8 12.9 V revert, 15 A of 500 Ah, 1 h;
    // SUNL 0.5 C; VIC-LFP no compensation, 5 degC; TAR #8 / LISHEN 0 degC;
    // SUNL / LBS 45 degC.
    {"lifepo4", 4, 14.2, 13.5, 12.9, false, 0.03, 1.0, 0.5, 0.0, 0.0, 5.0, 45.0, true},
    // LL / VIC-CHG Normal 14.4 V, LL 13.3 V float, MS/CONC 0.5 % C, MV 3 h,
    // TAR AGM -0.024 V/degC per 12 V, MS 0.4 C; lead-acid 50 degC (docs/batteries.md).
    {"agm", 6, 14.4, 13.3, 12.8, true, 0.005, 3.0, 0.4, -4.0, -45.0, -45.0, 50.0, false},
    // VIC-CHG High / TROJ 2.45 V/cell, TAR FLA 13.5 V, ROLLS 2 % C20, MV 4 h,
    // TAR / TROJ -5 mV/degC/cell, HP C/5.
    {"flooded", 6, 14.7, 13.5, 12.8, true, 0.02, 4.0, 0.2, -5.0, -45.0, -45.0, 50.0, false},
    // TROJ gel 2.40 / 2.25 V/cell, TAR gel 5 A of 500 Ah, MV 3 h, TROJ -5.
    {"gel", 6, 14.4, 13.5, 12.8, true, 0.01, 3.0, 0.2, -5.0, -45.0, -45.0, 50.0, false},
};

TEST(BatteryProfiles, EachProfileAt12_24_48VMatchesThePublishedTable) {
  for (const Row& row : kRows) {
    for (int nominal : {12, 24, 48}) {
      const int cells = row.cells12 * nominal / 12;
      const double cap = 300.0;
      const Config c = load(std::string("[battery]\nBatteryProfile = \"") + row.profile +
                            "\"\nBatteryCells = " + std::to_string(cells) + "\nBatteryCapacity_Ah = 300\n");
      const Params& p = c.params;
      const double k = nominal / 12.0;
      SCOPED_TRACE(std::string(row.profile) + " " + std::to_string(nominal) + " V");
      EXPECT_EQ(p.BatteryCells, cells);
      EXPECT_NEAR(p.BulkVoltage, row.absorption12 * k, 1e-9);
      EXPECT_NEAR(p.AbsorptionVoltage, row.absorption12 * k, 1e-9);
      EXPECT_NEAR(p.FloatVoltage, row.float12 * k, 1e-9);
      EXPECT_NEAR(p.RebulkVoltage, row.rebulk12 * k, 1e-9);
      EXPECT_EQ(p.UseFloat, row.useFloat);
      EXPECT_NEAR(p.TailCurrent_A, row.tailFraction * cap, 1e-9);
      EXPECT_EQ(p.AbsorptionTimeoutMs, static_cast<int>(row.hours * 3600000.0));
      EXPECT_NEAR(p.MaximumAllowedBatteryAmps, row.rateC * cap, 1e-9);
      EXPECT_DOUBLE_EQ(p.TempCompMvPerCellC, row.compMv);
      EXPECT_DOUBLE_EQ(p.ChargeMinTempC, row.minC);
      EXPECT_DOUBLE_EQ(p.ChargeFullCurrentTempC, row.fullC);
      EXPECT_DOUBLE_EQ(p.ChargeMaxTempC, row.maxC);
      EXPECT_EQ(p.BatteryTempRequired, row.tempRequired);
      // The 12 V alarm and full-charge voltages follow the bank: left at
      // their 0, derived from it.
      EXPECT_EQ(p.VoltageAlarmHigh, 0.0);
      EXPECT_NEAR(voltageAlarmHighV(p), std::max(15.0, row.absorption12 + 0.3) * k, 1e-9);
      EXPECT_NEAR(voltageAlarmLowV(p), 11.0 * k, 1e-9);
      EXPECT_NEAR(chargedVoltageV(p), 13.8 * k, 1e-9);
    }
  }
}

TEST(BatteryProfiles, CellsComeFromTheVoltageClassOfAFileBulkVoltage) {
  // 24 V class from the file's BulkVoltage: 8 LiFePO4 cells; the file's bulk stays.
  const Config c = load("[battery]\nBatteryProfile = \"lifepo4\"\n[voltage]\nBulkVoltage = 28.4\n");
  EXPECT_EQ(c.params.BatteryCells, 8);
  EXPECT_DOUBLE_EQ(c.params.BulkVoltage, 28.4);
  EXPECT_NEAR(c.params.FloatVoltage, 27.0, 1e-9);
  // No BulkVoltage, no BatteryCells: a 12 V bank.
  EXPECT_EQ(load("[battery]\nBatteryProfile = \"agm\"\n").params.BatteryCells, 6);
}

TEST(BatteryProfiles, FileValuesOverrideTheProfileAndCustomIsTodaysBehaviour) {
  const Config c = load(
      "[battery]\nBatteryProfile = \"lifepo4\"\n[voltage]\nAbsorptionVoltage = 14.0\nFloatVoltage = 13.4\n");
  EXPECT_DOUBLE_EQ(c.params.AbsorptionVoltage, 14.0);
  EXPECT_DOUBLE_EQ(c.params.FloatVoltage, 13.4);
  EXPECT_DOUBLE_EQ(c.params.BulkVoltage, 14.2);  // still the profile's
  EXPECT_TRUE(c.fileParamNames.count("AbsorptionVoltage"));
  EXPECT_TRUE(c.profileParamNames.count("BulkVoltage"));
  EXPECT_FALSE(c.profileParamNames.count("AbsorptionVoltage"));
  // custom (the default) fills nothing: exactly the catalogue defaults.
  const Config d = load("");
  EXPECT_EQ(d.params, Params{});
  EXPECT_TRUE(d.profileParamNames.empty());
  EXPECT_EQ(load("[battery]\nBatteryProfile = \"custom\"\n").params.BulkVoltage, Params{}.BulkVoltage);
}

TEST(BatteryProfiles, ReapplyingWithAnotherProfileMovesOnlyUnpinnedValues) {
  Params p = load("[battery]\nBatteryProfile = \"lifepo4\"\n[voltage]\nFloatVoltage = 13.4\n").params;
  p.BatteryProfile = static_cast<int>(BatteryProfileId::agm);
  ParamOrigins o;
  o.file = {"FloatVoltage"};
  o.dashboard = {"BatteryProfile"};
  const Params q = applyLayers(p, o);
  EXPECT_DOUBLE_EQ(q.AbsorptionVoltage, 14.4);
  EXPECT_DOUBLE_EQ(q.FloatVoltage, 13.4);  // the file's
  EXPECT_EQ(q.BatteryCells, 6);
  EXPECT_EQ(o.of("AbsorptionVoltage"), ParamSource::Profile);
  EXPECT_EQ(o.of("FloatVoltage"), ParamSource::File);
  EXPECT_EQ(o.of("BatteryProfile"), ParamSource::Dashboard);
  EXPECT_EQ(o.of("PidKp"), ParamSource::Default);
  // Back to custom: the profile's values return to the defaults.
  Params r = q;
  r.BatteryProfile = static_cast<int>(BatteryProfileId::custom);
  const Params s = applyLayers(r, o);
  EXPECT_DOUBLE_EQ(s.AbsorptionVoltage, Params{}.AbsorptionVoltage);
  EXPECT_TRUE(o.profile.empty());
}

bool names(const std::vector<ConfigError>& errs, const std::string& key, const std::string& words) {
  for (const auto& e : errs)
    if (e.key == key && e.message.find(words) != std::string::npos) return true;
  return false;
}

TEST(BatteryProfiles, LifepoAbsorptionAbove365PerCellIsRefusedNamingValueAndLimit) {
  // 14.6 V on 4 cells = 3.65 V/cell: at the limit, accepted.
  EXPECT_TRUE(errorsOf("[battery]\nBatteryProfile = \"lifepo4\"\n[voltage]\nBulkVoltage = 14.6\n"
                       "AbsorptionVoltage = 14.6\n")
                  .empty());
  // 14.64 V = 3.66 V/cell: just above, refused.
  const auto errs = errorsOf(
      "[battery]\nBatteryProfile = \"lifepo4\"\n[voltage]\nBulkVoltage = 14.64\n"
      "AbsorptionVoltage = 14.64\n");
  EXPECT_TRUE(names(errs, "voltage.AbsorptionVoltage", "14.64 V is 3.66 V/cell"));
  EXPECT_TRUE(names(errs, "voltage.AbsorptionVoltage", "3.65 V/cell"));
  // The same values with the custom profile are the user's business.
  EXPECT_TRUE(errorsOf("[battery]\nBatteryProfile = \"custom\"\n[voltage]\nBulkVoltage = 14.64\n"
                       "AbsorptionVoltage = 14.64\n")
                  .empty());
}

TEST(BatteryProfiles, FloatAboveAbsorptionAndInvertedTemperatureRangesAreRefused) {
  EXPECT_TRUE(names(errorsOf("[battery]\nBatteryProfile = \"agm\"\n[voltage]\nFloatVoltage = 14.5\n"),
                    "voltage.FloatVoltage", "is above AbsorptionVoltage 14.4 V"));
  EXPECT_TRUE(names(errorsOf("[battery]\nBatteryProfile = \"lifepo4\"\nChargeFullCurrentTempC = -1\n"),
                    "battery.ChargeMinTempC", "inverted"));
  EXPECT_TRUE(names(errorsOf("[battery]\nChargeMaxTempC = 10\nChargeFullCurrentTempC = 10\n"),
                    "battery.ChargeMaxTempC", "inverted"));
  EXPECT_TRUE(names(errorsOf("[battery]\nTempCompMinC = 40\nTempCompMaxC = 30\n"), "battery.TempCompMinC",
                    "inverted"));
  EXPECT_TRUE(names(errorsOf("[battery]\nBatteryProfile = \"lifepo4\"\nChargeMinTempC = -5\n"),
                    "battery.ChargeMinTempC", "below the LiFePO4 limit 0 °C"));
  // Just inside: min = full-current temperature is a step, not inverted.
  EXPECT_TRUE(errorsOf("[battery]\nBatteryProfile = \"lifepo4\"\nChargeFullCurrentTempC = 0\n").empty());
}

TEST(BatteryProfiles, AProfileIsWrittenByNameAndAnUnknownNameIsRefused) {
  EXPECT_TRUE(names(errorsOf("[battery]\nBatteryProfile = \"lithium\"\n"), "battery.BatteryProfile",
                    "\"lithium\" is not one of: lifepo4,agm,flooded,gel,custom"));
  EXPECT_TRUE(names(errorsOf("[battery]\nBatteryProfile = 1\n"), "battery.BatteryProfile", "quoted name"));
}

TEST(BatteryProfiles, PrintConfigNamesTheSourceOfEachValue) {
  const Config c = load("[battery]\nBatteryProfile = \"lifepo4\"\n[voltage]\nFloatVoltage = 13.4\n");
  ParamOrigins o;
  o.file = c.fileParamNames;
  o.dashboard = {"VoltageKp"};
  Params p = applyLayers(c.params, o);
  p.VoltageKp = 25.0;
  const std::string text = effectiveConfigText(c.settings, p, o);
  EXPECT_NE(text.find("BatteryProfile = \"lifepo4\"  # file\n"), std::string::npos);
  EXPECT_NE(text.find("FloatVoltage = 13.4  # file\n"), std::string::npos);
  EXPECT_NE(text.find("AbsorptionVoltage = 14.2  # profile\n"), std::string::npos);
  EXPECT_NE(text.find("VoltageKp = 25  # dashboard\n"), std::string::npos);
  EXPECT_NE(text.find("PidKp = 0.3  # default\n"), std::string::npos);
  // The printed text loads back to the same values.
  const LoadResult back = loadConfigString(text, "printed.toml");
  ASSERT_TRUE(back.ok()) << back.errors.front().toString();
  EXPECT_EQ(back.config->params, p);
}

// The packaged file writes every key: a profile chosen there is shadowed by
// those lines, and the user is told which (start log, --check-config).
TEST(BatteryProfile, TheValuesTheFilePinsOverTheProfileAreNamed) {
  const Config c = load(
      "[battery]\nBatteryProfile = \"agm\"\nBatteryCapacity_Ah = 200\n"
      "[voltage]\nAbsorptionVoltage = 14.3\nFloatVoltage = 13.3\nVoltageKp = 20\n");
  const auto v = profileValuesTheFileOverrides(c.params, c.fileParamNames);
  // FloatVoltage 13.3 is the AGM profile's own value: nothing to say.
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0], "AbsorptionVoltage = 14.3 (profile: 14.4)");
}

TEST(BatteryProfile, CustomOrAnUnpinnedFileShadowsNothing) {
  Config c = load("[battery]\nBatteryProfile = \"custom\"\n[voltage]\nAbsorptionVoltage = 14.3\n");
  EXPECT_TRUE(profileValuesTheFileOverrides(c.params, c.fileParamNames).empty());
  c = load("[battery]\nBatteryProfile = \"lifepo4\"\nBatteryCells = 8\n");
  EXPECT_TRUE(profileValuesTheFileOverrides(c.params, c.fileParamNames).empty());
}

TEST(BatteryProfile, A24VoltFileIsComparedWithThe24VoltProfile) {
  // BulkVoltage 28.8 makes a 24 V class; LiFePO4 at 8 cells absorbs at 28.4 V.
  const Config c = load(
      "[battery]\nBatteryProfile = \"lifepo4\"\n[voltage]\nBulkVoltage = 28.8\nAbsorptionVoltage = 28.4\n");
  const auto v = profileValuesTheFileOverrides(c.params, c.fileParamNames);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0], "BulkVoltage = 28.8 (profile: 28.4)");
}

}  // namespace
}  // namespace xr
