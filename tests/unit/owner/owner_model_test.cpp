// The owner model's one function: each limit with its amps and cause, the
// order (most restrictive first), the SoC rule and the state words.
#include "owner/owner_model.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace xr::owner {
namespace {

// AUTO in bulk, charging 40 A into the bank from a 120 A alternator whose
// RPM table tops at 100 A (the belt), nothing else acting.
Telemetry charging() {
  Telemetry t;
  t.mode = FieldControlMode::MODE_NORMAL_AUTO_PID;
  t.control.sysMode = SysMode::SYS_MODE_AUTO;
  t.stage = ChargeStage::BULK;
  t.field_enable = true;
  t.alt_a = 45.0;
  t.bcur_a = 40.0;
  t.battery_v = 13.4;
  t.caps.ratingA = 120.0;
  t.caps.rpmTableA = 100.0;
  t.caps.rpmTableTopA = 100.0;
  t.caps.batteryMaxA = 300.0;
  t.caps.commandA = 100.0;
  return t;
}

const OwnerLimit* find(const std::vector<OwnerLimit>& l, std::string_view id) {
  auto it = std::find_if(l.begin(), l.end(), [&](const OwnerLimit& x) { return x.id == id; });
  return it == l.end() ? nullptr : &*it;
}

TEST(OwnerLimits, NoProbeOnLiFePO4ListsTheC10CapWithItsAmpsAndCause) {
  Telemetry t = charging();
  t.caps.batteryTempA = 28.0;
  t.caps.batteryTempCause = BatteryTempCap::NO_PROBE;
  const auto m = ownerModel(t);
  ASSERT_FALSE(m.limits.empty());
  EXPECT_EQ(m.limits.front().id, "battery_temp_required");
  EXPECT_EQ(m.limits.front().what, "C/10 without a battery probe");
  EXPECT_DOUBLE_EQ(m.limits.front().amps, 28.0);
  EXPECT_NE(m.limits.front().why.find("battery temperature sensor"), std::string::npos);
  EXPECT_EQ(m.state, "Charging · Bulk · limited by C/10 without a battery probe");
  EXPECT_EQ(limitedByText(m), "C/10 without a battery probe: 28 A");
}

TEST(OwnerLimits, EachCapOfTheCommandChainAppearsWithItsAmps) {
  Telemetry t = charging();
  t.caps.batteryTempA = 50.0;
  t.caps.batteryTempCause = BatteryTempCap::COLD_RAMP;
  t.caps.bmsA = 60.0;
  t.bms_state = BmsState::OK;
  t.caps.bmsSource = BmsSource::Can;
  t.caps.thermalA = 70.0;
  t.caps.batteryMaxA = 110.0;
  t.caps.warmupA = 30.0;
  t.caps.fastOvA = 20.0;
  const auto l = ownerLimits(t, {});
  const std::pair<const char*, double> want[] = {
      {"voltage_spike", 20.0},  {"warmup", 30.0}, {"battery_cold_ramp", 50.0}, {"bms_ccl", 60.0},
      {"thermal_derate", 70.0}, {"belt", 100.0},  {"battery_max", 110.0}};
  ASSERT_EQ(l.size(), std::size(want));
  for (std::size_t i = 0; i < l.size(); ++i) {
    EXPECT_EQ(l[i].id, want[i].first) << i;
    EXPECT_DOUBLE_EQ(l[i].amps, want[i].second) << i;
    EXPECT_FALSE(l[i].what.empty());
    EXPECT_FALSE(l[i].why.empty());
  }
}

TEST(OwnerLimits, MostRestrictiveFirstWithTheNonCurrentLimitsLeading) {
  Telemetry t = charging();
  t.mode = FieldControlMode::MODE_NORMAL_MANUAL;
  t.caps.batteryTempA = 28.0;
  t.caps.batteryTempCause = BatteryTempCap::NO_PROBE;
  const auto l = ownerLimits(t, {false, "at most 14.0 V"});
  ASSERT_GE(l.size(), 3u);
  EXPECT_EQ(l[0].id, "manual");
  EXPECT_EQ(l[1].id, "not_set_up");
  EXPECT_NE(l[1].why.find("at most 14.0 V"), std::string::npos);
  EXPECT_EQ(l[2].id, "battery_temp_required");
  for (std::size_t i = 3; i < l.size(); ++i) EXPECT_LE(l[i - 1].amps, l[i].amps);
}

TEST(OwnerLimits, TheRpmTableBelowItsTopIsTheEngineSpeedNotTheBelt) {
  Telemetry t = charging();
  t.caps.rpmTableA = 35.0;
  const auto l = ownerLimits(t, {});
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(l[0].id, "rpm_table");
  EXPECT_DOUBLE_EQ(l[0].amps, 35.0);
}

TEST(OwnerLimits, ACapAtOrAboveTheAlternatorRatingHoldsNothingBack) {
  Telemetry t = charging();
  t.caps.rpmTableTopA = t.caps.rpmTableA = 120.0;
  t.caps.commandA = 120.0;
  t.caps.bmsA = 200.0;  // a CCL above what this alternator gives
  t.bms_state = BmsState::OK;
  const auto l = ownerLimits(t, {});
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(l[0].id, "alternator_rating");
  EXPECT_DOUBLE_EQ(l[0].amps, 120.0);
}

TEST(OwnerLimits, AVictronGxLimitIsDvccAndASilentBmsItsFallback) {
  Telemetry t = charging();
  t.caps.bmsA = 45.0;
  t.bms_state = BmsState::OK;
  t.caps.bmsSource = BmsSource::VictronGx;
  EXPECT_NE(find(ownerLimits(t, {}), "dvcc"), nullptr);
  t.bms_state = BmsState::STALE;
  t.caps.bmsSource = BmsSource::Can;
  EXPECT_NE(find(ownerLimits(t, {}), "bms_silent"), nullptr);
}

TEST(OwnerLimits, WeatherHoldAndSwitchedOffAreZeroAmpHolds) {
  Telemetry t;
  t.mode = FieldControlMode::MODE_DISABLED_RAMP;
  t.reason = Reason::REASON_WEATHER_MODE;
  auto m = ownerModel(t);
  ASSERT_EQ(m.limits.size(), 1u);
  EXPECT_EQ(m.limits[0].id, "weather_hold");
  EXPECT_DOUBLE_EQ(m.limits[0].amps, 0.0);
  EXPECT_EQ(m.state, "Not charging · Weather mode: solar first");
  t.reason = Reason::REASON_SYS_OFF;
  m = ownerModel(t);
  EXPECT_EQ(m.limits.at(0).id, "switched_off");
}

TEST(OwnerLimits, OutsideAutoTheCommandPathCapsAreNotListed) {
  Telemetry t = charging();
  t.mode = FieldControlMode::MODE_DISABLED_RAMP;
  t.reason = Reason::REASON_RPM_LOW;
  t.field_enable = false;
  t.caps.rpmTableA = 10.0;  // last AUTO tick's: not this one's
  const auto m = ownerModel(t);
  EXPECT_TRUE(m.limits.empty());
  EXPECT_EQ(m.state, "Not charging · Engine stopped or idling");
}

TEST(OwnerSoc, ATalkingBmsIsTheSocThenCountedThenEstimateThenUnknown) {
  Telemetry t;
  t.soc_pct = 91.0;
  t.battery.socSource = SocSource::Counted;
  t.bms_soc_pct = 40.0;
  t.bms_state = BmsState::OK;
  EXPECT_DOUBLE_EQ(ownerSoc(t).pct, 40.0);
  EXPECT_EQ(ownerSoc(t).source, "bms");
  t.bms_state = BmsState::STALE;  // a silent BMS's last SoC is not the SoC
  EXPECT_DOUBLE_EQ(ownerSoc(t).pct, 91.0);
  EXPECT_EQ(ownerSoc(t).source, "counted");
  t.battery.socSource = SocSource::OcvEstimate;
  EXPECT_EQ(ownerSoc(t).source, "ocv_estimate");
  t.battery.socSource = SocSource::Unknown;
  EXPECT_TRUE(std::isnan(ownerSoc(t).pct));
  EXPECT_EQ(ownerSoc(t).source, "unknown");
}

TEST(OwnerSoc, TheCsvColumnFollowsTheSameRuleAndIsEmptyWhileUnknown) {
  Telemetry t;
  t.soc_pct = 100.0;  // the monitor's start value, not known
  t.battery.socSource = SocSource::Unknown;
  double csv = 0.0;
  visitTelemetryColumns(t, 0, [&](std::string_view n, const ColumnValue& v) {
    if (n == "soc_pct") csv = std::get<double>(v);
  });
  EXPECT_TRUE(std::isnan(csv));
  t.bms_state = BmsState::OK;
  t.bms_soc_pct = 40.0;
  visitTelemetryColumns(t, 0, [&](std::string_view n, const ColumnValue& v) {
    if (n == "soc_pct") csv = std::get<double>(v);
  });
  EXPECT_DOUBLE_EQ(csv, 40.0);
}

TEST(OwnerHero, ChargingShowsTheBatteryCurrentRestingTheSocOrTheVoltage) {
  Telemetry t = charging();
  auto h = ownerModel(t).hero;
  EXPECT_DOUBLE_EQ(h.value, 40.0);
  EXPECT_EQ(h.unit, "A");
  EXPECT_EQ(h.label, "into the battery");
  t.field_enable = false;
  t.bms_state = BmsState::OK;
  t.bms_soc_pct = 40.0;
  h = ownerModel(t).hero;
  EXPECT_EQ(h.unit, "%");
  EXPECT_DOUBLE_EQ(h.value, 40.0);
  t.bms_state = BmsState::OFF;
  h = ownerModel(t).hero;
  EXPECT_EQ(h.unit, "V");
  EXPECT_DOUBLE_EQ(h.value, 13.4);
}

TEST(OwnerState, NotSetUpLeadsTheStateAndTheBmsHasOneWord) {
  Telemetry t = charging();
  t.bms_state = BmsState::OK;
  t.caps.bmsSource = BmsSource::Can;
  const auto m = ownerModel(t, {false, ""});
  EXPECT_EQ(m.state.rfind("Not set up · Charging · Bulk", 0), 0u);
  EXPECT_EQ(m.bms.state, "talking");
  EXPECT_EQ(m.bms.words, "talking (CAN)");
  t.bms_state = BmsState::OFF;
  EXPECT_EQ(ownerModel(t).bms.state, "none");
}

// Not set up on a 24 V bank: one calm notice naming the size to choose, in
// the state's notice and in the "Not set up" limit; no number from an
// unread bank.
TEST(OwnerModel, NotSetUpNoticeNamesTheBankSizeTheBatteryReads) {
  Telemetry t;
  t.setupBank = {true, 26.04, 24, true};
  const OwnerModel m = ownerModel(t, {false, "at most 28 V"});
  EXPECT_EQ(m.notice, "The bank reads 26.0 V: choose 24 V on the set-up page.");
  const auto it = std::find_if(m.limits.begin(), m.limits.end(),
                               [](const OwnerLimit& l) { return l.id == "not_set_up"; });
  ASSERT_NE(it, m.limits.end());
  EXPECT_NE(it->why.find("choose 24 V on the set-up page"), std::string::npos) << it->why;
}

TEST(OwnerModel, NotSetUpNoticeSaysTheTwelveVoltLimitsStayForAReadingThatFitsNoBank) {
  Telemetry t;
  t.setupBank = {true, 18.0, 12, false};
  const std::string n = ownerModel(t, {false, ""}).notice;
  EXPECT_NE(n.find("18.0 V, which fits no 12, 24 or 48 V bank"), std::string::npos) << n;
  EXPECT_NE(n.find("12 V limits"), std::string::npos) << n;
  t.setupBank = {true, kNoValue, 12, false};
  const std::string none = ownerModel(t, {false, ""}).notice;
  EXPECT_EQ(none.find("nan"), std::string::npos) << none;
  EXPECT_NE(none.find("No battery voltage reading"), std::string::npos) << none;
}

TEST(OwnerModel, NoNoticeOnceSetUpOrWhenTheBankWasNotRead) {
  Telemetry t;
  t.setupBank = {true, 26.0, 24, true};
  EXPECT_TRUE(ownerModel(t, {true, ""}).notice.empty());
  EXPECT_TRUE(ownerModel(Telemetry{}, {false, ""}).notice.empty());
}

}  // namespace
}  // namespace xr::owner
