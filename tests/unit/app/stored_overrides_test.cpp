// the file and the dashboard's stored overrides are checked
// as ONE set, at start and by --check-config; an override that no longer fits
// is dropped with an event naming it.
#include "app/stored_overrides.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "app/config_check.h"
#include "app/effective_params.h"
#include "app/store_service.h"
#include "config/config.h"
#include "store/param_overrides.h"
#include "store_test_util.h"
#include "test_files.h"

namespace xr::app {
namespace {

using ::testing::HasSubstr;
using xr::test::kT0;
using xr::test::TempDir;

OverrideRow row(std::string name, std::string value, std::int64_t at = kT0) {
  return OverrideRow{std::move(name), std::move(value), "", at};
}

TEST(StoredOverrides, AStoredFloatAboveALoweredFileAbsorptionIsDroppedAndTheSetRunsConsistent) {
  // PATCH FloatVoltage 14.3 was accepted; then the file lowered
  // AbsorptionVoltage to 14.0: Float 14.3 > Absorption 14.0 must not run.
  Params file;
  file.AbsorptionVoltage = 14.0;
  const NameSet fileNames{"AbsorptionVoltage"};  // the file wrote it
  ASSERT_TRUE(checkConsistency(file).empty());
  const auto r = resolveStoredOverrides(file, fileNames, {row("FloatVoltage", "14.3")});
  EXPECT_TRUE(checkConsistency(r.params).empty());
  EXPECT_DOUBLE_EQ(r.params.FloatVoltage, file.FloatVoltage);
  ASSERT_EQ(r.dropped.size(), 1u);
  EXPECT_EQ(r.dropped[0].name, "FloatVoltage");
  EXPECT_THAT(r.dropped[0].text(), HasSubstr("stored dashboard setting FloatVoltage = 14.3 dropped"));
  EXPECT_THAT(r.dropped[0].text(), HasSubstr("is above AbsorptionVoltage 14 V"));
}

TEST(StoredOverrides, AtTheLimitTheOverrideStaysJustAboveItIsDropped) {
  Params file;
  file.AbsorptionVoltage = 14.0;
  const NameSet fileNames{"AbsorptionVoltage"};  // the file wrote it
  EXPECT_TRUE(resolveStoredOverrides(file, fileNames, {row("FloatVoltage", "14")}).dropped.empty());
  EXPECT_DOUBLE_EQ(resolveStoredOverrides(file, fileNames, {row("FloatVoltage", "14")}).params.FloatVoltage,
                   14.0);
  EXPECT_EQ(resolveStoredOverrides(file, fileNames, {row("FloatVoltage", "14.01")}).dropped.size(), 1u);
}

TEST(StoredOverrides, OverridesThatOnlyFitTogetherAreKeptTogether) {
  // One PATCH raised Bulk and Absorption together: each alone would be fine
  // with the file, both together must stay.
  const Params file;
  const NameSet fileNames;
  const auto r =
      resolveStoredOverrides(file, fileNames, {row("BulkVoltage", "14.6"), row("AbsorptionVoltage", "14.6")});
  EXPECT_TRUE(r.dropped.empty());
  EXPECT_DOUBLE_EQ(r.params.AbsorptionVoltage, 14.6);
  EXPECT_DOUBLE_EQ(r.params.BulkVoltage, 14.6);
}

TEST(StoredOverrides, OnlyTheOffendingOneOfSeveralIsDropped) {
  Params file;
  file.AbsorptionVoltage = 14.0;
  const NameSet fileNames{"AbsorptionVoltage"};  // the file wrote it
  const auto r = resolveStoredOverrides(
      file, fileNames,
      {row("FloatVoltage", "14.3"), row("MaxDuty", "90"), row("Gone", "1"), row("BulkVoltage", "999")});
  EXPECT_TRUE(checkConsistency(r.params).empty());
  EXPECT_DOUBLE_EQ(r.params.MaxDuty, 90.0);
  std::vector<std::string> names;
  for (const auto& d : r.dropped) names.push_back(d.name);
  EXPECT_THAT(names, ::testing::UnorderedElementsAre("FloatVoltage", "Gone", "BulkVoltage"));
}

TEST(StoredOverrides, StoreServiceForgetsADroppedOverrideAndRecordsAnEvent) {
  TempDir d;
  const std::string db = d.file("x.db");
  Params file;
  {
    Store s;
    ASSERT_TRUE(s.open(db, kT0).ok);
    Params operatorSet = file;
    operatorSet.FloatVoltage = 14.3;
    operatorSet.MaxDuty = 90;
    ASSERT_TRUE(saveParamOverride(s, "FloatVoltage", file, operatorSet, kT0).ok);
    ASSERT_TRUE(saveParamOverride(s, "MaxDuty", file, operatorSet, kT0).ok);
  }
  file.AbsorptionVoltage = 14.0;  // the file changed under the stored Float
  const NameSet fileNames{"AbsorptionVoltage"};
  {
    StoreService svc(db, 300);
    const auto r = svc.applyOverrides(file, fileNames);
    EXPECT_TRUE(checkConsistency(r.params).empty());
    EXPECT_DOUBLE_EQ(r.params.MaxDuty, 90.0);
    ASSERT_EQ(r.dropped.size(), 1u);
    const auto events = svc.queryEvents(10, std::nullopt);
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events[0].code, "OverrideDropped");
    EXPECT_EQ(events[0].level, "warning");
    EXPECT_THAT(events[0].message, HasSubstr("FloatVoltage = 14.3 dropped"));
    svc.stop(BatteryLedger{}, false);
  }
  Store s;
  ASSERT_TRUE(s.open(db, kT0).ok);
  EXPECT_FALSE(s.findOverride("FloatVoltage").has_value());  // forgotten: no repeat at every start
  EXPECT_TRUE(s.findOverride("MaxDuty").has_value());
}

// The set-up page stores the battery type among the overrides. At the next
// start the set is judged as it will run, the profile re-applied: LiFePO4
// with the catalogue's custom values (a -45 degC charge limit) alone would
// fail the LiFePO4 check and the owner's choice would be lost.
TEST(StoredOverrides, ASetUpChoiceOfLifepo4SurvivesTheNextStart) {
  TempDir d;
  const std::string db = d.file("x.db");
  const Params file;  // the shipped file: no battery chosen
  const NameSet fileNames;
  {
    Store s;
    ASSERT_TRUE(s.open(db, kT0).ok);
    Params chosen = file;
    chosen.BatteryProfile = static_cast<int>(BatteryProfileId::lifepo4);
    chosen.BatteryCapacity_Ah = 280;
    ASSERT_TRUE(saveParamOverride(s, "BatteryProfile", file, chosen, kT0).ok);
    ASSERT_TRUE(saveParamOverride(s, "BatteryCapacity_Ah", file, chosen, kT0).ok);
  }
  StoreService svc(db, 300);
  const auto r = svc.applyOverrides(file, fileNames);
  EXPECT_TRUE(r.dropped.empty()) << (r.dropped.empty() ? "" : r.dropped[0].text());
  ParamOrigins origins;
  std::string why;
  const Params running = withDashboardLayer(file, r, origins, &why);
  EXPECT_EQ(why, "");
  EXPECT_EQ(running.BatteryProfile, static_cast<int>(BatteryProfileId::lifepo4));
  EXPECT_DOUBLE_EQ(running.BatteryCapacity_Ah, 280.0);
  EXPECT_TRUE(checkConsistency(running).empty());
  EXPECT_TRUE(origins.setUp());
  EXPECT_TRUE(svc.queryEvents(10, std::nullopt).empty()) << "nothing dropped, nothing to say";
  svc.stop(BatteryLedger{}, false);
}

TEST(StoredOverrides, CheckConfigReadsTheStateDatabaseAndWarnsWithoutChangingIt) {
  TempDir d;
  const std::string db = d.file("x.db");
  {
    Store s;
    ASSERT_TRUE(s.open(db, kT0).ok);
    Params operatorSet;
    operatorSet.FloatVoltage = 14.3;
    ASSERT_TRUE(saveParamOverride(s, "FloatVoltage", Params{}, operatorSet, kT0).ok);
  }
  xr::testing::TempFile cfg("[voltage]\nAbsorptionVoltage = 14.0\n");
  std::ostringstream out, err;
  // Before the fix --check-config said OK without a word: the override
  // would make an inconsistent set.
  EXPECT_EQ(checkConfigAndState(cfg.path(), db, out, err), 0);  // the daemon will start, dropping it
  EXPECT_THAT(out.str(), HasSubstr("FloatVoltage = 14.3 dropped"));
  EXPECT_THAT(out.str(), HasSubstr("0 stored dashboard settings fit the configuration, 1 will be dropped"));
  std::string why;
  EXPECT_EQ(readOverridesReadOnly(db, &why).size(), 1u);  // read-only: still there
  EXPECT_EQ(why, "");

  xr::testing::TempFile fine("[voltage]\nAbsorptionVoltage = 14.4\n");
  std::ostringstream out2, err2;
  EXPECT_EQ(checkConfigAndState(fine.path(), db, out2, err2), 0);
  EXPECT_THAT(out2.str(), HasSubstr("1 stored dashboard setting fit the configuration"));
  EXPECT_THAT(out2.str(), ::testing::Not(HasSubstr("dropped")));

  std::ostringstream out3, err3;
  EXPECT_EQ(checkConfigAndState(fine.path(), d.file("none.db"), out3, err3), 0);  // first start
}

}  // namespace
}  // namespace xr::app
