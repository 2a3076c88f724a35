// Belt slip with the alternator's tach alone (docs/operations.md "Belt
// slip", sign C): no engine speed on NMEA 2000, RpmSource = tach. A belt
// that slips speeds the alternator up when the probe holds its current low;
// an engine that slows, a load step or a thermal derate does not.
#include <gtest/gtest.h>

#include <cstdio>

#include "closed_loop.h"

namespace xr::sim::test {
namespace {

SimRunResult runTachOnly(const std::string& toml) {
  SimRunOptions o;
  o.scenario = parseScenario(toml, "belt_tach.toml");
  o.telemetryRateHz = 1.0;
  o.settings.can.RpmSource = "tach";
  SimRunner r(o);
  SimRunResult res = r.run();
  EXPECT_EQ(res.inaProtocolErrors, 0u);
  EXPECT_FALSE(res.finalFieldEnable);
  return res;
}

std::vector<Event> beltSlips(const SimRunResult& r) {
  std::vector<Event> out;
  for (const Event& e : r.events)
    if (e.code == EventCode::BeltSlip) out.push_back(e);
  return out;
}

// Bulk into a LiFePO4 bank at a steady 1800 rpm, the alternator at its
// rated output (the regulator set up for it, as an installer would).
std::string cruise(const std::string& extra) {
  return std::string(R"(name = "belt, tach only"
duration_s = 900
seed = 9
[config]
BatteryProfile = "lifepo4"
BatteryCapacity_Ah = 400
MaxTableValue = 120
rpmCapCurrentTable = [0, 120, 120, 120, 120, 120, 120, 120, 120, 120]
[battery]
chemistry = "lifepo4"
capacity_ah = 400
soc_pct = 40
temp_sensor = true
[alternator]
rated_a = 120
temp_f = 80
ambient_f = 85
[engine]
rpm = 1800
[loads]
house_a = 5
)") + extra;
}

TEST(BeltSlipTachAlone, HalfSlipAtRatedOutputGivesOneEventWithinTenMinutes) {
  const SimRunResult r = runTachOnly(cruise(R"([[events]]
at_s = 300
fault = "belt_slip"
value = 0.5
)"));
  const auto slips = beltSlips(r);
  ASSERT_EQ(slips.size(), 1u) << trace(r, 10);
  std::printf("%s at %.1f s\n", describe(slips[0]).c_str(), toSec(slips[0].t));
  EXPECT_EQ(slips[0].detail, 3);
  EXPECT_GT(toSec(slips[0].t), 300.0);
  EXPECT_LT(toSec(slips[0].t), 900.0);
  EXPECT_EQ(r.rows.back().telemetry.wear.belt_slip_events, 1.0);
  // Charging carries on after the probe: the owner is told, the bank still charged.
  EXPECT_GT(at(r, 880)->plant.alt_a, 30.0) << trace(r, 10);
}

TEST(BeltSlipTachAlone, SpeedChangesAndLoadStepsGiveNone) {
  const SimRunResult r = runTachOnly(cruise(R"([[events]]
at_s = 120
rpm = 2600
[[events]]
at_s = 240
rpm = 900
[[events]]
at_s = 360
rpm = 3000
[[events]]
at_s = 480
rpm = 1200
[[events]]
at_s = 600
rpm = 2000
[[events]]
at_s = 660
house_a = 60
[[events]]
at_s = 720
rpm = 1300
[[events]]
at_s = 780
house_a = 5
[[events]]
at_s = 840
rpm = 600
)"));
  EXPECT_EQ(beltSlips(r).size(), 0u) << trace(r, 10);
}

TEST(BeltSlipTachAlone, AThermalDerateGivesNone) {
  // Sustained full output on a hot day: the thermal loop takes current off
  // at a steady speed (as ClosedLoop.SustainedThermalDerateKeepsAlternatorBelowWarning).
  const SimRunResult r = runTachOnly(R"(name = "derate, tach only"
duration_s = 3600
seed = 14
[battery]
chemistry = "lifepo4"
capacity_ah = 800
soc_pct = 20
[alternator]
rated_a = 55
temp_f = 110
ambient_f = 110
[engine]
rpm = 1800
[loads]
house_a = 5
)");
  // The run must derate to mean anything: a penalty, and the current down by 5 A or more.
  EXPECT_GT(maxOf(r, [](const SimRow& w) { return w.telemetry.thermal_penalty_a; }), 0.5) << trace(r, 120);
  EXPECT_LT(r.rows.back().plant.alt_a, maxOf(r, [](const SimRow& w) { return w.plant.alt_a; }) - 5.0);
  EXPECT_EQ(beltSlips(r).size(), 0u) << trace(r, 60);
}

}  // namespace
}  // namespace xr::sim::test
