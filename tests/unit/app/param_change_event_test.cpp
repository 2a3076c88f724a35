// a settings change is an event naming each value, old ->
// new, and who asked; it is kept across a restart like every other event.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "app/param_change_text.h"
#include "app/store_service.h"
#include "app/web_api.h"
#include "store_test_util.h"
#include "web_api_rig.h"

namespace xr::app {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using xr::test::TempDir;

TEST(ParamChangeText, NamesEachValueOldToNewAndTheSource) {
  Params before, after;
  after.FloatVoltage = 13.3;
  after.UseFloat = !before.UseFloat;
  after.rpmCapCurrentTable[3] = before.rpmCapCurrentTable[3] + 5.0;
  const std::string t =
      paramChangeText(before, after, {"FloatVoltage", "UseFloat", "rpmCapCurrentTable"}, "device \"Anna\"");
  EXPECT_THAT(t, HasSubstr("by device \"Anna\""));
  EXPECT_THAT(t,
              HasSubstr("FloatVoltage " + std::to_string(before.FloatVoltage).substr(0, 4) + " \u2192 13.3"));
  EXPECT_THAT(t, HasSubstr(std::string("UseFloat ") + (before.UseFloat ? "on \u2192 off" : "off \u2192 on")));
  EXPECT_THAT(t, HasSubstr("rpmCapCurrentTable point 4 "));
  // Only the changed point of the table is listed.
  EXPECT_THAT(t, Not(HasSubstr("point 3 ")));
  EXPECT_THAT(t, Not(HasSubstr("follows")));
}

TEST(ParamChangeText, ValuesMovedByTheProfileSaySoAndNothingChangedIsEmpty) {
  Params before, after;
  after.AbsorptionVoltage = before.AbsorptionVoltage - 0.2;
  EXPECT_THAT(paramChangeText(before, after, {"BatteryProfile"}, "x"),
              HasSubstr("(follows the battery profile)"));
  EXPECT_EQ(paramChangeText(before, before, {"FloatVoltage"}, "x"), "");
  // No binary-double noise (13.300000000000001).
  after = before;
  after.FloatVoltage = 13.1 + 0.2;
  EXPECT_THAT(paramChangeText(before, after, {"FloatVoltage"}, "x"), HasSubstr("\u2192 13.3"));
  EXPECT_THAT(paramChangeText(before, after, {"FloatVoltage"}, "x"), Not(HasSubstr("0000")));
}

using Rig = test::WebApiRig;

web::ParamChange change(const char* name, double v, int index = -1) { return {findParam(name), index, v}; }

TEST(WebApiParamEvents, AnAppliedPatchIsAStoredEventThatSurvivesARestart) {
  TempDir d;
  const std::string db = d.file("x.db");
  {
    Rig r(db);
    ASSERT_TRUE(r.api->patchParams({change("MaxDuty", 80)}, "device \"Anna's phone\"").errors.empty());
  }
  Rig second(db);
  web::EventQuery q;
  const auto events = second.api->events(q);
  ASSERT_FALSE(events.empty());
  EXPECT_THAT(events[0].text, HasSubstr("Settings changed by device \"Anna's phone\": MaxDuty "));
  EXPECT_THAT(events[0].text, HasSubstr("\u2192 80"));
  EXPECT_EQ(events[0].event.level, EventLevel::Info);
}

TEST(WebApiParamEvents, ARefusedOrEmptyPatchMakesNoEvent) {
  Rig r;  // no store: the in-memory list serves
  EXPECT_FALSE(r.api->patchParams({change("FloatVoltage", 14.9)}, "x").errors.empty());  // above Absorption
  const double same = r.api->currentParams().MaxDuty;
  ASSERT_TRUE(r.api->patchParams({change("MaxDuty", same)}, "x").errors.empty());
  EXPECT_TRUE(r.api->events(web::EventQuery{}).empty());
  ASSERT_TRUE(r.api->patchParams({change("MaxDuty", same - 1)}, "the installer token").errors.empty());
  const auto events = r.api->events(web::EventQuery{});
  ASSERT_EQ(events.size(), 1u);
  EXPECT_THAT(events[0].text, HasSubstr("by the installer token: MaxDuty"));
}

// The set-up page's save is one event line, not one line per value
// (about 40 with the RPM tables).
TEST(WebApiParamEvents, TheSetUpIsOneEventLine) {
  Rig r;
  std::vector<web::ParamChange> setup{change("BatteryProfile", 0), change("BatteryCells", 4),
                                      change("BatteryCapacity_Ah", 280), change("MaxTableValue", 120)};
  for (int i = 1; i < static_cast<int>(RPM_TABLE_SIZE); ++i)
    setup.push_back(change("rpmCapCurrentTable", 100, i));
  ASSERT_TRUE(r.api->patchParams(setup, "device \"Anna\"").errors.empty());
  const auto events = r.api->events(web::EventQuery{});
  ASSERT_EQ(events.size(), 1u);
  EXPECT_THAT(events[0].text, HasSubstr("Set-up: LiFePO4 12 V 280 Ah, alternator 120 A, belt 100 A"));
  EXPECT_EQ(events[0].text.find('\n'), std::string::npos);
  EXPECT_THAT(events[0].text, Not(HasSubstr("rpmCapCurrentTable")));
}

}  // namespace
}  // namespace xr::app
