// One validation of a PATCH, the daemon's (app/web_api_params.cpp): the web
// server only parses, and the set-up page asks with a dry run what a
// chemistry and a bank give instead of knowing the profiles' rules
// (docs/dashboard.md "Set-up").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "app/web_api.h"
#include "config/battery_profiles.h"
#include "store_test_util.h"
#include "web_api_rig.h"

namespace xr::app {
namespace {

using ::testing::HasSubstr;
using xr::test::TempDir;
using Rig = test::WebApiRig;

web::ParamChange change(const char* name, double v) { return {findParam(name), -1, v}; }
constexpr web::PatchOptions kDryRun{true, 0};
web::PatchOptions dryRunForBank(int v) { return {true, v}; }

void measure(Rig& r, double batteryV) {
  rt::RuntimeSnapshot snap;
  snap.tick = 1;
  snap.telemetry.battery_v = batteryV;
  r.handoffs.snapshot.store(snap);
}

bool names(const web::PatchResult& r, const std::string& name, const std::string& words = "") {
  for (const auto& e : r.errors)
    if (e.name == name && e.message.find(words) != std::string::npos) return true;
  return false;
}

// 12 V AGM: the profile's bulk, absorption and float voltages, as the
// catalogue's profile table gives them; nothing applied, stored or told.
TEST(WebApiDryRun, AnswersTheProfilesVoltagesForTheChosenBankAndKeepsNothing) {
  TempDir d;
  Rig r(d.file("x.db"));
  measure(r, 12.9);
  const Params before = r.api->currentParams();
  const std::size_t eventsBefore = r.recent.query(100, 0).size();
  const auto res = r.api->patchParams({change("BatteryProfile", 1)}, "test", dryRunForBank(12));  // agm
  ASSERT_TRUE(res.errors.empty()) << res.errors[0].message;
  ASSERT_TRUE(res.values);
  const ProfileTable* agm = profileTable(BatteryProfileId::agm);
  EXPECT_DOUBLE_EQ(res.values->BulkVoltage, agm->bulkV12);
  EXPECT_DOUBLE_EQ(res.values->BulkVoltage, 14.4);  // docs/batteries.md, AGM
  EXPECT_DOUBLE_EQ(res.values->AbsorptionVoltage, agm->absorptionV12);
  EXPECT_DOUBLE_EQ(res.values->FloatVoltage, agm->floatV12);
  EXPECT_EQ(res.values->BatteryCells, 6);
  EXPECT_EQ(r.api->currentParams(), before);
  EXPECT_EQ(r.recent.query(100, 0).size(), eventsBefore) << "a dry run made an event";
  EXPECT_TRUE(r.store->applyOverrides(Params{}, NameSet{}).applied.empty()) << "a dry run stored a value";
}

// The same chemistry on a 24 V bank: twice the cells and twice the voltages.
TEST(WebApiDryRun, ABankChoiceGivesTheChemistryItsCellsForThatBank) {
  Rig r;
  measure(r, 26.1);
  const auto res = r.api->patchParams({change("BatteryProfile", 1)}, "test", dryRunForBank(24));
  ASSERT_TRUE(res.errors.empty()) << res.errors[0].message;
  EXPECT_EQ(res.values->BatteryCells, 12);
  EXPECT_DOUBLE_EQ(res.values->BulkVoltage, 2 * profileTable(BatteryProfileId::agm)->bulkV12);
  // Saved for real, the daemon holds what the dry run answered.
  ASSERT_TRUE(r.api->patchParams({change("BatteryProfile", 1)}, "test", {false, 24}).errors.empty());
  EXPECT_DOUBLE_EQ(r.api->currentParams().BulkVoltage, res.values->BulkVoltage);
  EXPECT_EQ(r.api->currentParams().BatteryCells, 12);
}

// Custom (no chemistry): the owner's own voltages move to the other bank.
TEST(WebApiDryRun, ACustomSetMovesItsVoltagesToTheChosenBank) {
  Rig r;
  ASSERT_TRUE(
      r.api->patchParams({change("BatteryProfile", 4), change("BulkVoltage", 14.6)}, "test").errors.empty());
  measure(r, 26.1);
  const auto res = r.api->patchParams({}, "test", dryRunForBank(24));
  ASSERT_TRUE(res.errors.empty()) << res.errors[0].message;
  EXPECT_DOUBLE_EQ(res.values->BulkVoltage, 29.2);
  EXPECT_DOUBLE_EQ(res.values->FloatVoltage, 2 * r.api->currentParams().FloatVoltage);
}

// A bad combination is answered with its errors: a 24 V set-up on a bank
// measuring 12 V, a bank that does not exist; nothing applied.
TEST(WebApiDryRun, ABadCombinationIsAnsweredWithItsErrors) {
  Rig r;
  measure(r, 12.9);
  const Params before = r.api->currentParams();
  const auto res = r.api->patchParams({change("BatteryProfile", 0)}, "test", dryRunForBank(24));  // lifepo4
  EXPECT_TRUE(names(res, "BulkVoltage", "measures as a 12 V bank"));
  ASSERT_TRUE(res.values);
  EXPECT_EQ(res.values->BatteryCells, 8);
  EXPECT_TRUE(names(r.api->patchParams({}, "test", dryRunForBank(30)), "bank"));
  EXPECT_EQ(r.api->currentParams(), before);
}

// The catalogue's ranges are checked here (the server no longer does), with
// the configuration file's words.
TEST(WebApiPatch, EachValueIsCheckedAgainstTheCatalogueOnce) {
  Rig r;
  const Params before = r.api->currentParams();
  auto res = r.api->patchParams({change("FloatVoltage", 999), change("PidSampleDivisor", 1.5)}, "test");
  EXPECT_TRUE(names(res, "FloatVoltage", "out of range: allowed 8 to 64 V"));
  EXPECT_TRUE(names(res, "PidSampleDivisor", "not a whole number"));
  EXPECT_FALSE(res.values);
  web::ParamChange cell{findParam("rpmCapCurrentTable"), 3, -5.0};
  EXPECT_TRUE(names(r.api->patchParams({cell}, "test"), "rpmCapCurrentTable", "element 3"));
  EXPECT_EQ(r.api->currentParams(), before);
  EXPECT_TRUE(r.api->patchParams({change("FloatVoltage", 999)}, "test", kDryRun).errors.size() == 1);
}

// A voltage of another bank size is refused by the checks of the whole set,
// at the class boundary too (18 V is the first 24 V value); a difference
// of voltages is not a battery voltage.
TEST(WebApiPatch, AVoltageForAnotherBankSizeIsRefused) {
  Rig r;
  measure(r, 12.9);
  auto bulk = r.api->patchParams({change("BulkVoltage", 28.8)}, "test");
  EXPECT_TRUE(names(bulk, "BulkVoltage", "measures as a 12 V bank"));
  EXPECT_TRUE(names(r.api->patchParams({change("VoltageAlarmHigh", 18.0)}, "test"), "VoltageAlarmHigh",
                    "is for a 24 V bank"));
  EXPECT_DOUBLE_EQ(r.api->currentParams().VoltageAlarmHigh, Params{}.VoltageAlarmHigh);
  EXPECT_TRUE(r.api->patchParams({change("VoltageAlarmHigh", 17.9)}, "test").errors.empty());
  EXPECT_TRUE(r.api->patchParams({change("VoltageDisagreeThreshold", 2.0)}, "test").errors.empty());
}

}  // namespace
}  // namespace xr::app
