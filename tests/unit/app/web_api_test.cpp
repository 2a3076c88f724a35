// Hardening (docs/security.md) through the daemon's side of the web API (app/web_api.cpp):
// history bounds, a change that cannot be saved is refused (the store's
// state is shown), events of earlier runs, bare error keys.
#include "app/web_api.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "app/config_check.h"
#include "app/store_service.h"
#include "store/sqlite_db.h"
#include "store_test_util.h"
#include "test_files.h"
#include "web_api_rig.h"

namespace xr::app {
namespace {

using ::testing::HasSubstr;
using xr::test::TempDir;

using Rig = test::WebApiRig;

web::ParamChange change(const char* name, double v) { return {findParam(name), -1, v}; }

TEST(WebApiHistory, AbsurdStepFromAndToAreRejectedBeforeAnyConversion) {
  TempDir d;
  Rig r(d.file("x.db"));
  const double now = 1.7e9;
  auto ask = [&](double from, double to, double step) {
    web::HistoryQuery q;
    q.series = {"ibv_v"};
    q.from_s = from;
    q.to_s = to;
    q.step_s = step;
    return r.api->history(q);
  };
  // The reproducers: before, 100,000 points per series (and UB).
  for (auto res : {ask(now - 3600, now, 1e300), ask(-1e300, now, 1e300), ask(now, 1e300, 1e299),
                   ask(now - 3600, now, std::nan("")), ask(now - 3600, now, 0.5)}) {
    EXPECT_FALSE(res.error.empty());
    EXPECT_TRUE(res.t.empty());
  }
  EXPECT_THAT(ask(now - 3600, now, 0.1).error, HasSubstr("step must be 1 s"));
  // At the point limit: 10,000 steps are fine, one more is not.
  EXPECT_EQ(ask(now - 10000, now, 1).error, "");
  EXPECT_EQ(ask(now - 10000, now, 1).t.size(), 10001u);
  EXPECT_THAT(ask(now - 10001, now, 1).error, HasSubstr("too many points"));
}

TEST(WebApiPatch, CrossParameterErrorsUseBareNames) {
  Rig r;
  const auto res =
      r.api->patchParams({change("FloatVoltage", 14.6)}, "test");  // above the default Absorption
  ASSERT_FALSE(res.errors.empty());
  EXPECT_EQ(res.errors[0].name, "FloatVoltage");  // before: "voltage.FloatVoltage"
}

TEST(WebApiPatch, AChangeThatCannotBeSavedIsRefusedAndNotApplied) {
  TempDir d;
  // Its "directory" is a regular file: the store falls back to memory, as
  // with a read-only state directory (and independent of running as root).
  { std::ofstream(d.file("afile")) << "x"; }
  Rig r(d.file("afile/x.db"));
  ASSERT_FALSE(r.store->status().persistent);
  const double before = r.api->currentParams().MaxDuty;
  const auto res = r.api->patchParams({change("MaxDuty", 80)}, "test");
  ASSERT_EQ(res.errors.size(), 1u);  // before: no error, lost at the next start
  EXPECT_EQ(res.errors[0].name, "store");
  EXPECT_THAT(res.errors[0].message, HasSubstr("would be lost at the next start"));
  EXPECT_DOUBLE_EQ(r.api->currentParams().MaxDuty, before);
  EXPECT_THAT(r.api->versions()["store"], HasSubstr("NOT SAVING"));
}

// A PATCH of two values whose second row cannot be written (a trigger
// planted in the database refuses it): nothing is applied and nothing of it
// is saved, so the next start runs what the answer said (before: the first
// row stayed saved while the API answered "nothing applied").
TEST(WebApiPatch, AChangeIsSavedWholeOrNotAtAll) {
  TempDir d;
  Rig r(d.file("x.db"));
  {
    sql::Db raw;
    ASSERT_EQ(raw.open(d.file("x.db")), SQLITE_OK);
    ASSERT_EQ(raw.exec("CREATE TRIGGER planted BEFORE INSERT ON overrides WHEN NEW.name = 'FloatVoltage' "
                       "BEGIN SELECT RAISE(ABORT, 'planted failure'); END"),
              SQLITE_OK);
  }
  const Params before = r.api->currentParams();
  const auto res =
      r.api->patchParams({change("AbsorptionVoltage", 14.3), change("FloatVoltage", 13.3)}, "test");
  ASSERT_EQ(res.errors.size(), 1u);
  EXPECT_EQ(res.errors[0].name, "store");
  EXPECT_THAT(res.errors[0].message, HasSubstr("cannot save FloatVoltage"));
  EXPECT_EQ(r.api->currentParams(), before);
  EXPECT_TRUE(r.store->applyOverrides(Params{}, NameSet{}).applied.empty())
      << "AbsorptionVoltage was saved alone";
}

TEST(WebApiPatch, AChangeThatIsSavedIsAppliedAndTheStoreShowsOk) {
  TempDir d;
  Rig r(d.file("x.db"));
  EXPECT_TRUE(r.api->patchParams({change("MaxDuty", 80)}, "test").errors.empty());
  EXPECT_DOUBLE_EQ(r.api->currentParams().MaxDuty, 80.0);
  EXPECT_THAT(r.api->versions()["store"], HasSubstr("ok: "));
}

TEST(WebApiEvents, EventsOfAnEarlierRunAreShownAndPaged) {
  TempDir d;
  const std::string db = d.file("x.db");
  {
    Rig first(db);
    for (int i = 0; i < 3; ++i) {
      Event e;
      e.code = EventCode::FieldOn;
      first.store->appendEvent(e);
    }
  }
  Rig second(db);  // a restart: the in-memory ring is empty
  web::EventQuery q;
  q.limit = 2;
  const auto page = second.api->events(q);
  ASSERT_EQ(page.size(), 2u);  // before: 0
  EXPECT_EQ(page[0].event.code, EventCode::FieldOn);
  EXPECT_GT(page[0].id, page[1].id);
  q.before = page[1].id;
  const auto older = second.api->events(q);
  ASSERT_EQ(older.size(), 1u);
  EXPECT_LT(older[0].id, page[1].id);
}

TEST(WebApiEvents, EveryCodeComesBackFromTheStoreByName) {
  // The codes after AlarmCondition (battery temperature, CAN) read back as
  // Message before: the name parse stopped there.
  TempDir d;
  Rig rig(d.file("x.db"));
  for (EventCode c : {EventCode::BatteryTempBack, EventCode::BmsBadFrames, EventCode::CanErrorFrames}) {
    Event e;
    e.code = c;
    rig.store->appendEvent(e);
  }
  web::EventQuery q;
  const auto got = rig.api->events(q);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0].event.code, EventCode::CanErrorFrames);
  EXPECT_EQ(got[1].event.code, EventCode::BmsBadFrames);
  EXPECT_EQ(got[2].event.code, EventCode::BatteryTempBack);
}

}  // namespace
}  // namespace xr::app

// PATCH /api/params and the battery profile.
namespace xr::app {
namespace {

TEST(WebApiProfiles, AProfileChangeMovesItsValuesAndNamesTheirSources) {
  TempDir d;
  Rig r(d.file("p.db"));
  const auto res = r.api->patchParams({change("BatteryProfile", 0)}, "test");  // lifepo4
  ASSERT_TRUE(res.errors.empty()) << res.errors[0].message;
  const Params p = r.api->currentParams();
  EXPECT_DOUBLE_EQ(p.AbsorptionVoltage, 14.2);
  EXPECT_EQ(p.UseFloat, false);
  const auto src = r.api->paramSources();
  EXPECT_EQ(src.at("BatteryProfile"), "dashboard");
  EXPECT_EQ(src.at("AbsorptionVoltage"), "profile");
  EXPECT_EQ(src.at("PidKp"), "default");
  // Only the named value is stored: the profile's follow it at the next start.
  ASSERT_TRUE(r.store);
}

TEST(WebApiProfiles, ABadProfileValueIsRefusedAndNothingApplied) {
  Rig r;
  ASSERT_TRUE(r.api->patchParams({change("BatteryProfile", 0)}, "test").errors.empty());
  const Params before = r.api->currentParams();
  // 14.8 V on 4 LiFePO4 cells = 3.7 V/cell, over the 3.65 V/cell limit.
  const auto res =
      r.api->patchParams({change("AbsorptionVoltage", 14.8), change("BulkVoltage", 14.8)}, "test");
  ASSERT_FALSE(res.errors.empty());
  bool named = false;
  for (const auto& e : res.errors)
    named |= e.name == "AbsorptionVoltage" && e.message.find("3.65 V/cell") != std::string::npos;
  EXPECT_TRUE(named);
  EXPECT_EQ(r.api->currentParams(), before);
  // An inverted temperature range, too.
  EXPECT_FALSE(r.api->patchParams({change("ChargeMaxTempC", 4.0)}, "test").errors.empty());
  EXPECT_EQ(r.api->currentParams(), before);
}

// The set-up page's save, as the owner makes it: a chemistry chosen over a
// float voltage typed on the settings page earlier. The PATCH's null drops
// that value, so the profile's applies, and nothing of it stays stored.
TEST(WebApiProfiles, ANullDropsTheDashboardValueSoTheProfileAppliesAgain) {
  TempDir d;
  Rig r(d.file("p.db"));
  ASSERT_TRUE(r.api->patchParams({change("FloatVoltage", 13.2)}, "test").errors.empty());
  EXPECT_EQ(r.api->paramSources().at("FloatVoltage"), "dashboard");
  web::ParamChange drop{findParam("FloatVoltage"), -1, 0.0, true};
  const auto res = r.api->patchParams({change("BatteryProfile", 1), drop}, "test");  // agm
  ASSERT_TRUE(res.errors.empty()) << res.errors[0].message;
  EXPECT_DOUBLE_EQ(r.api->currentParams().FloatVoltage, 13.3);  // the AGM profile's, not 13.2
  EXPECT_EQ(r.api->paramSources().at("FloatVoltage"), "profile");
  const auto stored = r.store->applyOverrides(Params{}, NameSet{}).applied;
  EXPECT_THAT(stored, ::testing::Contains("BatteryProfile"));
  EXPECT_THAT(stored, ::testing::Not(::testing::Contains("FloatVoltage")));
  EXPECT_TRUE(r.api->profileOwned().contains("FloatVoltage"));
  EXPECT_FALSE(r.api->profileOwned().contains("PidKp"));
}

// "Default" on the Settings page is the value the battery profile gives the
// bank the owner has, not the firmware's and not what the dashboard set.
TEST(WebApiProfiles, TheEffectiveDefaultIsTheProfilesValueForTheBank) {
  TempDir d;
  Rig r(d.file("p.db"));
  ASSERT_TRUE(
      r.api->patchParams({change("BatteryProfile", 1), change("FloatVoltage", 13.2)}, "test").errors.empty());
  Params eff = r.api->effectiveDefaults();
  EXPECT_DOUBLE_EQ(eff.FloatVoltage, 13.3);  // AGM's 12 V float, not the dashboard's 13.2
  EXPECT_NE(eff.FloatVoltage, Params{}.FloatVoltage);
  rt::RuntimeSnapshot snap;
  snap.tick = 1;
  snap.telemetry.battery_v = 26.1;
  r.handoffs.snapshot.store(snap);
  // The 12 V float the dashboard pinned would not fit a 24 V bank: dropped with it.
  web::ParamChange drop{findParam("FloatVoltage"), -1, 0.0, true};
  const auto res = r.api->patchParams({change("BatteryCells", 12), drop}, "test");
  ASSERT_TRUE(res.errors.empty()) << res.errors[0].message;
  eff = r.api->effectiveDefaults();
  EXPECT_DOUBLE_EQ(eff.FloatVoltage, 26.6);  // the same profile on a 24 V bank
}

// A set for another bank than the one measured is refused as a whole: the
// set-up's 24 V LiFePO4 (BatteryCells = 8) on a bank reading 12.9 V, which
// names no voltage itself.
TEST(WebApiPatch, ASetForAnotherBankThanTheMeasuredOneIsRefused) {
  Rig r;
  rt::RuntimeSnapshot snap;
  snap.tick = 1;
  snap.telemetry.battery_v = 12.9;
  r.handoffs.snapshot.store(snap);
  const Params before = r.api->currentParams();
  const auto res = r.api->patchParams({change("BatteryProfile", 0), change("BatteryCells", 8)}, "test");
  ASSERT_EQ(res.errors.size(), 1u);
  EXPECT_EQ(res.errors[0].name, "BulkVoltage");
  EXPECT_THAT(res.errors[0].message, HasSubstr("for a 24 V bank"));
  EXPECT_THAT(res.errors[0].message, HasSubstr("measures as a 12 V bank"));
  EXPECT_EQ(r.api->currentParams(), before);
  // The same on a 24 V bank is accepted, with the profile's 24 V values.
  snap.telemetry.battery_v = 26.1;
  r.handoffs.snapshot.store(snap);
  ASSERT_TRUE(
      r.api->patchParams({change("BatteryProfile", 0), change("BatteryCells", 8)}, "test").errors.empty());
  EXPECT_DOUBLE_EQ(r.api->currentParams().AbsorptionVoltage, 28.4);
}

}  // namespace
}  // namespace xr::app

// Not set up (docs/configuration.md "Not set up"): a fresh install runs
// within the limits safe for every battery; choosing the battery type on the
// set-up page lifts them at once, from what the file and the dashboard
// really say, and leaves one event.
namespace xr::app {
namespace {

TEST(NotSetUp, AFreshInstallRunsLoweredAndSaysSo) {
  Rig r({}, false);
  const Params p = r.api->currentParams();
  EXPECT_DOUBLE_EQ(p.BulkVoltage, 14.0);
  EXPECT_DOUBLE_EQ(p.FloatVoltage, 13.4);
  EXPECT_DOUBLE_EQ(p.ChargeMinTempC, 5.0);
  EXPECT_EQ(r.api->paramSources().at("BulkVoltage"), "not set up");
  EXPECT_EQ(r.api->paramSources().at("PidKp"), "default");
  const auto s = r.api->setupState();
  EXPECT_FALSE(s.setUp);
  EXPECT_THAT(s.limits, HasSubstr("at most 14 V, float 13.4 V"));
}

TEST(NotSetUp, AVoltageSetBeforeTheBatteryIsChosenStaysLowered) {
  Rig r({}, false);
  ASSERT_TRUE(r.api->patchParams({change("BulkVoltage", 14.6)}, "test").errors.empty());
  EXPECT_DOUBLE_EQ(r.api->currentParams().BulkVoltage, 14.0);
  EXPECT_FALSE(r.api->setupState().setUp);
}

TEST(NotSetUp, ChoosingTheBatteryLiftsTheLimitsFromTheValuesSetBelowThem) {
  Rig r({}, false);
  ASSERT_TRUE(r.api->patchParams({change("BulkVoltage", 14.6)}, "test").errors.empty());
  ASSERT_TRUE(r.api->patchParams({change("BatteryProfile", 4)}, "test").errors.empty());  // custom
  const Params p = r.api->currentParams();
  EXPECT_DOUBLE_EQ(p.BulkVoltage, 14.6);  // the owner's value, not the lowered 14.0
  EXPECT_DOUBLE_EQ(p.FloatVoltage, 13.5);
  EXPECT_DOUBLE_EQ(p.ChargeMinTempC, -45.0);
  EXPECT_TRUE(r.api->setupState().setUp);
  EXPECT_EQ(r.api->paramSources().at("FloatVoltage"), "default");
  int lifted = 0;
  for (const auto& e : r.api->events(web::EventQuery{}))
    lifted += e.text.find("limits are lifted") != std::string::npos;
  EXPECT_EQ(lifted, 1);
}

// The reproducer: on the shipped file, PATCH {"TargetVoltageMode": true,
// "TargetVoltageSetpoint": 14.8} answered 200 and ran at 14.8 V; after
// BulkVoltage 14.6, 14.9 was accepted.
TEST(NotSetUp, ATargetAboveTheLoweredSetIsRefusedByPatchAtItsThreshold) {
  Rig r({}, false);
  auto res =
      r.api->patchParams({change("TargetVoltageMode", 1), change("TargetVoltageSetpoint", 14.8)}, "test");
  ASSERT_EQ(res.errors.size(), 1u);
  EXPECT_EQ(res.errors[0].name, "TargetVoltageSetpoint");
  EXPECT_THAT(res.errors[0].message, HasSubstr("while not set up"));
  EXPECT_FALSE(r.api->currentParams().TargetVoltageMode) << "nothing applied";
  ASSERT_TRUE(r.api->patchParams({change("BulkVoltage", 14.6)}, "test").errors.empty());
  EXPECT_FALSE(r.api->patchParams({change("TargetVoltageSetpoint", 14.9)}, "test").errors.empty());
  EXPECT_FALSE(r.api->patchParams({change("TargetVoltageSetpoint", 14.01)}, "test").errors.empty());
  EXPECT_FALSE(r.api->patchParams({change("ChargedVoltage", 14.2)}, "test").errors.empty());
  EXPECT_FALSE(r.api->patchParams({change("RebulkVoltage", 13.45)}, "test").errors.empty());
  // At the limit: taken, and what runs is never above it.
  ASSERT_TRUE(
      r.api->patchParams({change("TargetVoltageMode", 1), change("TargetVoltageSetpoint", 14.0)}, "test")
          .errors.empty());
  const Params p = r.api->currentParams();
  EXPECT_DOUBLE_EQ(p.TargetVoltageSetpoint, 14.0);
  EXPECT_DOUBLE_EQ(p.SetupCeilingV, 14.0);
  // Once set up, the owner's 14.5 V setpoint is theirs to choose.
  ASSERT_TRUE(r.api->patchParams({change("BatteryProfile", 4), change("TargetVoltageSetpoint", 14.5)}, "test")
                  .errors.empty());
  EXPECT_DOUBLE_EQ(r.api->currentParams().TargetVoltageSetpoint, 14.5);
  EXPECT_DOUBLE_EQ(r.api->currentParams().SetupCeilingV, 0.0);
}

// The same in the file passed --check-config, and a 4 h run targeted 14.9 V.
TEST(NotSetUp, CheckConfigRefusesAFileTargetAboveTheLoweredSet) {
  TempDir d;
  xr::testing::TempFile bad(
      "[voltage]\nBulkVoltage = 14.6\nTargetVoltageSetpoint = 14.9\n[modes]\nTargetVoltageMode = true\n");
  std::ostringstream out, err;
  EXPECT_EQ(checkConfigAndState(bad.path(), d.file("none.db"), out, err), 78);
  EXPECT_THAT(err.str(), HasSubstr("voltage.TargetVoltageSetpoint: TargetVoltageSetpoint 14.9 V is above"));
  // Named battery: set up, the same file is fine.
  xr::testing::TempFile chosen(
      "[voltage]\nBulkVoltage = 14.6\nTargetVoltageSetpoint = 14.9\n[battery]\nBatteryProfile = "
      "\"custom\"\n");
  std::ostringstream out2, err2;
  EXPECT_EQ(checkConfigAndState(chosen.path(), d.file("none.db"), out2, err2), 0) << err2.str();
  // At the limit: fine.
  xr::testing::TempFile edge("[voltage]\nTargetVoltageSetpoint = 14.0\n");
  std::ostringstream out3, err3;
  EXPECT_EQ(checkConfigAndState(edge.path(), d.file("none.db"), out3, err3), 0) << err3.str();
}

TEST(NotSetUp, AFileThatNamesTheBatteryIsSetUp) {
  Rig r;  // as daemon.cpp with a file naming BatteryProfile
  EXPECT_TRUE(r.api->setupState().setUp);
  EXPECT_DOUBLE_EQ(r.api->currentParams().BulkVoltage, 14.5);
}

}  // namespace
}  // namespace xr::app
