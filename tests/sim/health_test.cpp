// What the regulator learns, on the simulated boat (docs/batteries.md
// "Measured capacity", "Internal resistance"; docs/operations.md "Belt
// slip"): the scenario's [battery] capacity_ah is the truth and
// [config] BatteryCapacity_Ah what the owner typed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "closed_loop.h"

namespace xr::sim::test {
namespace {

SimRunOptions optionsFor(const std::string& toml, double rateHz, const std::string& n2k = "",
                         const std::string& rpmSource = "tach", std::optional<std::uint64_t> seed = {}) {
  SimRunOptions o;
  o.scenario = parseScenario(toml, "health.toml");
  o.telemetryRateHz = rateHz;
  o.settings.can.n2k_interface = n2k;
  o.settings.can.RpmSource = rpmSource;
  o.seed = seed;
  return o;
}

SimRunResult run(const SimRunOptions& o) {
  SimRunner r(o);
  SimRunResult res = r.run();
  EXPECT_EQ(res.inaProtocolErrors, 0u);
  EXPECT_FALSE(res.finalFieldEnable);
  return res;
}

SimRunResult runWith(const std::string& toml, double rateHz, const std::string& n2k = "",
                     const std::string& rpmSource = "tach") {
  return run(optionsFor(toml, rateHz, n2k, rpmSource));
}

// Days of a bank, at the health days' 100 Hz loop.
SimRunResult runDays(const std::string& toml, double rateHz, std::optional<std::uint64_t> seed = {}) {
  SimRunOptions o = optionsFor(toml, rateHz, "", "tach", seed);
  o.settings.runtime.control_period_us = kHealthDaysControlPeriodUs;
  return run(o);
}

int count(const SimRunResult& r, EventCode c) {
  int n = 0;
  for (const Event& e : r.events) n += e.code == c;
  return n;
}

// An owner's two days on an AGM bank that has lost a fifth of its 200 Ah:
// a charge, a quiet evening, a night on the fridge and lights, a rest, the
// engine again, and the same once more.
constexpr const char* kAgm160 = R"(name = "AGM that holds 160 Ah, set up as 200 Ah"
duration_s = 138600
seed = 5
[config]
BatteryProfile = "agm"
BatteryCapacity_Ah = 200
[battery]
chemistry = "agm"
capacity_ah = 160
soc_pct = 92
temp_sensor = true
[alternator]
rated_a = 100
temp_f = 80
ambient_f = 85
[engine]
rpm = 1600
[loads]
house_a = 5
[[events]]
at_s = 14400
rpm = 0
house_a = 1
[[events]]
at_s = 36000
house_a = 25
[[events]]
at_s = 45200
house_a = 1
[[events]]
at_s = 66960
rpm = 1600
house_a = 5
[[events]]
at_s = 84960
rpm = 0
house_a = 1
[[events]]
at_s = 106560
house_a = 25
[[events]]
at_s = 115760
house_a = 1
)";

TEST(MeasuredCapacity, AnAgmBankSetUpAs200AhMeasures160Ah) {
  const SimRunResult r = runDays(kAgm160, 0.02);
  ASSERT_FALSE(r.rows.empty());
  const auto& last = r.rows.back().telemetry.battery;
  std::printf("measured %.1f Ah over %d swings (truth 160 Ah)\n", last.capacity_measured_ah,
              last.capacity_cycles);
  EXPECT_GE(last.capacity_cycles, 2) << trace(r, 3600);
  EXPECT_NEAR(last.capacity_measured_ah, 160.0, 16.0) << trace(r, 3600);
  // Never a number from one swing: before the second, no figure.
  for (const SimRow& w : r.rows) {
    if (w.telemetry.battery.capacity_cycles < 2) {
      EXPECT_TRUE(std::isnan(w.telemetry.battery.capacity_measured_ah));
    }
  }
  EXPECT_GE(count(r, EventCode::CapacityMeasured), 2);
}

// LiFePO4 with a BMS on CAN that reports its SoC: the BMS's SoC is the known point.
constexpr const char* kLfp160 = R"(name = "LiFePO4 that holds 160 Ah, set up as 200 Ah, BMS on CAN"
duration_s = 57600
seed = 6
[config]
BatteryProfile = "lifepo4"
BatteryCapacity_Ah = 200
[battery]
chemistry = "lifepo4"
capacity_ah = 160
soc_pct = 90
[alternator]
rated_a = 100
temp_f = 80
ambient_f = 85
[engine]
rpm = 1600
[loads]
house_a = 5
[bms]
can = true
protocol = "pylontech"
[[events]]
at_s = 7200
rpm = 0
house_a = 25
[[events]]
at_s = 16200
house_a = 1
[[events]]
at_s = 23400
rpm = 1600
house_a = 5
[[events]]
at_s = 34200
rpm = 0
house_a = 25
[[events]]
at_s = 43200
house_a = 1
)";

TEST(MeasuredCapacity, ALifepo4BankWithABmsMeasures160Ah) {
  const SimRunResult r = runDays(kLfp160, 0.02);
  ASSERT_FALSE(r.rows.empty());
  const auto& last = r.rows.back().telemetry.battery;
  std::printf("measured %.1f Ah over %d swings (truth 160 Ah)\n", last.capacity_measured_ah,
              last.capacity_cycles);
  EXPECT_GE(last.capacity_cycles, 2) << trace(r, 3600);
  EXPECT_NEAR(last.capacity_measured_ah, 160.0, 16.0) << trace(r, 3600);
}

// A day at anchor on a 200 Ah AGM bank: the fridge, lights, a pump and the
// watermaker switch on and off; the engine does not run.
std::string loadDay() {
  std::ostringstream s;
  s << R"(name = "a day of load steps"
duration_s = 86400
seed = 1
[config]
BatteryProfile = "agm"
BatteryCapacity_Ah = 200
[battery]
chemistry = "agm"
capacity_ah = 200
soc_pct = 95
temp_sensor = true
[alternator]
rated_a = 100
[engine]
rpm = 0
[loads]
house_a = 1
)";
  const double loads[] = {6.0, 12.0, 8.0, 15.0, 7.0, 10.0};
  int i = 0;
  for (int t = 900; t + 600 < 86400; t += 900, ++i) {
    s << "[[events]]\nat_s = " << t << "\nhouse_a = " << loads[i % 6] << "\n";
    s << "[[events]]\nat_s = " << t + 300 << "\nhouse_a = 1\n";
  }
  return s.str();
}

TEST(BatteryResistance, ADayOfLoadStepsGivesThePlantsR0PlusR1) {
  // Plant: a 12 V 200 Ah AGM bank has R0 = 0.5 ohm-Ah / 200 Ah = 2.5 mOhm at
  // 25 degC and R1 = 0.5 R0 (drivers/sim/plant/battery.cpp): R0 + R1 = 3.75 mOhm.
  const double truth = 3.75;
  double lo = 1e9, hi = 0.0;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const SimRunResult r = runDays(loadDay(), 0.01, seed);
    ASSERT_FALSE(r.rows.empty());
    const auto& b = r.rows.back().telemetry.battery;
    std::printf("seed %u: %.3f mOhm (spread %.3f, %d samples; truth %.2f)\n", static_cast<unsigned>(seed),
                b.battery_r_mohm, b.battery_r_spread_mohm, b.battery_r_samples, truth);
    EXPECT_GE(b.battery_r_samples, 5) << "seed " << seed;
    EXPECT_NEAR(b.battery_r_mohm, truth, 0.25 * truth) << "seed " << seed;
    EXPECT_LT(b.battery_r_spread_mohm, 0.25 * truth) << "seed " << seed;
    lo = std::min(lo, b.battery_r_mohm);
    hi = std::max(hi, b.battery_r_mohm);
  }
  // Stable across noise seeds: the three medians within 5 % of each other.
  EXPECT_LT(hi - lo, 0.05 * truth) << lo << ".." << hi;
}

// Bulk into a LiFePO4 bank at cruising speed; the engine's ECU on NMEA 2000.
std::string beltScenario(const std::string& events) {
  return std::string(R"(name = "belt"
duration_s = 900
seed = 8
[config]
BatteryProfile = "lifepo4"
BatteryCapacity_Ah = 400
MaxTableValue = 120
rpmCapCurrentTable = [0, 80, 80, 80, 80, 80, 80, 80, 80, 80]
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
ecu = true
[loads]
house_a = 5
)") + events;
}

constexpr const char* kSlip = R"([[events]]
at_s = 400
fault = "belt_slip"
value = 0.8
)";

TEST(BeltSlip, TheTachAgainstTheEngineGivesOneEvent) {
  const SimRunResult r = runWith(beltScenario(kSlip), 1.0, "can1", "tach");
  int n = 0;
  for (const Event& e : r.events)
    if (e.code == EventCode::BeltSlip) {
      ++n;
      EXPECT_EQ(e.detail, 1);
      std::printf("%s at %.1f s\n", describe(e).c_str(), toSec(e.t));
      EXPECT_GT(toSec(e.t), 400.0);
      EXPECT_LT(toSec(e.t), 440.0);
    }
  EXPECT_EQ(n, 1) << trace(r, 20);
  EXPECT_EQ(r.rows.back().telemetry.wear.belt_slip_events, 1.0);
}

TEST(BeltSlip, CurrentFallingWhileTheFieldRisesGivesOneEvent) {
  // RpmSource = n2k: the speed the regulator reads is the engine's, steady.
  const SimRunResult r = runWith(beltScenario(kSlip), 1.0, "can1", "n2k");
  int n = 0;
  for (const Event& e : r.events)
    if (e.code == EventCode::BeltSlip) {
      ++n;
      EXPECT_EQ(e.detail, 2);
      std::printf("%s at %.1f s\n", describe(e).c_str(), toSec(e.t));
      EXPECT_GT(toSec(e.t), 400.0);
    }
  EXPECT_EQ(n, 1) << trace(r, 20);
}

TEST(BeltSlip, OrdinarySpeedChangesGiveNone) {
  const std::string steps = R"([[events]]
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
at_s = 720
house_a = 60
)";
  for (const char* source : {"tach", "n2k"}) {
    const SimRunResult r = runWith(beltScenario(steps), 1.0, "can1", source);
    EXPECT_EQ(count(r, EventCode::BeltSlip), 0) << source << "\n" << trace(r, 20);
  }
}

}  // namespace
}  // namespace xr::sim::test
