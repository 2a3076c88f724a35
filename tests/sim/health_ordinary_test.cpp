// Health figures from what a cruising boat really does (docs/batteries.md
// "Measured capacity", "Internal resistance"): an aged AGM bank that holds
// 160 Ah, set up as 200 Ah, on three patterns of two to three days that
// differ in their loads, the fridge's cycling and when the engine stops,
// one with solar. Each run is shared by every assertion on it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "closed_loop.h"

namespace xr::sim::test {
namespace {

// An engine run: hours after 07:00 it starts, and how long it runs.
struct EngineRun {
  double atH, hours;
};

// One day of the boat, from 07:00: the engine runs, the day at anchor draws
// `dayA`, the evening `eveningA` from 18:00 for `eveningH` hours, the night
// `nightA`; the fridge cycles on top all the time.
struct Day {
  std::vector<EngineRun> runs;
  double dayA, eveningA, eveningH, nightA;
};

struct Pattern {
  const char* name;
  double socPct;
  double fridgeA, fridgeDuty, fridgePeriodS;
  double solarA;  // a solar controller's current at noon (0 = none)
  std::uint64_t seed;
  std::vector<Day> days;
  double endH;  // hours after the start of the last day the run ends
};

void scenarioHead(std::ostringstream& s, const Pattern& p, double dur) {
  s << "name = \"" << p.name << "\"\nduration_s = " << dur << "\nseed = " << p.seed << R"(
[config]
BatteryProfile = "agm"
BatteryCapacity_Ah = 200
[battery]
chemistry = "agm"
capacity_ah = 160
soc_pct = )"
    << p.socPct << R"(
temp_sensor = true
[alternator]
rated_a = 100
temp_f = 80
ambient_f = 85
[engine]
rpm = 0
[loads]
house_a = )"
    << p.days.front().dayA << "\nfridge_a = " << p.fridgeA << "\nfridge_duty = " << p.fridgeDuty
    << "\nfridge_period_s = " << p.fridgePeriodS << "\n";
  // A controller set to the bank, as an installer would: the sun from 06:00
  // to 20:00, the run starting at 07:00.
  if (p.solarA > 0.0)
    s << "[solar]\nmax_a = " << p.solarA << "\nabsorption_v = 14.4\nfloat_v = 13.4\nstart_h = 7\n";
}

std::string scenarioOf(const Pattern& p) {
  std::ostringstream s;
  const double dur = 86400.0 * double(p.days.size() - 1) + p.endH * 3600.0;
  scenarioHead(s, p, dur);
  auto ev = [&](double t, const std::string& what) {
    if (t < dur) s << "[[events]]\nat_s = " << t << "\n" << what << "\n";
  };
  for (std::size_t i = 0; i < p.days.size(); ++i) {
    const Day& d = p.days[i];
    const double t0 = 86400.0 * double(i);
    ev(t0, "house_a = " + std::to_string(d.dayA));
    for (const EngineRun& r : d.runs) {
      ev(t0 + r.atH * 3600.0 + 1.0, "rpm = 1600");
      ev(t0 + (r.atH + r.hours) * 3600.0, "rpm = 0");
    }
    ev(t0 + 11.0 * 3600.0, "house_a = " + std::to_string(d.eveningA));               // 18:00
    ev(t0 + (11.0 + d.eveningH) * 3600.0, "house_a = " + std::to_string(d.nightA));  // the night
  }
  return s.str();
}

// The plant's 160 Ah AGM bank: R0 = 0.5 ohm-Ah / 160 Ah = 3.125 mOhm at
// 25 degC and R1 = 0.5 R0 (drivers/sim/plant/battery.cpp): what a step read
// after a minute and a half sees, 4.69 mOhm.
constexpr double kTrueRmohm = 3.125 * 1.5;

struct Outcome {
  double capacityAh, rMohm, socPct, trueSocPct;
  int cycles, rSamples;
};

Outcome run(const Pattern& p) {
  SimRunOptions o;
  o.scenario = parseScenario(scenarioOf(p), "ordinary.toml");
  o.telemetryRateHz = 0.01;
  // At 100 Hz: 120.4 Ah and 4.58 mOhm on a trial pattern at both rates.
  o.settings.runtime.control_period_us = kHealthDaysControlPeriodUs;
  const std::clock_t c0 = std::clock();
  SimRunner r(o);
  const SimRunResult res = r.run();
  EXPECT_EQ(res.inaProtocolErrors, 0u);
  EXPECT_FALSE(res.finalFieldEnable);
  EXPECT_FALSE(res.rows.empty());
  if (res.rows.empty()) return {};
  const auto& b = res.rows.back().telemetry.battery;
  Outcome out{b.capacity_measured_ah,        b.battery_r_mohm,  res.rows.back().telemetry.soc_pct,
              res.rows.back().plant.soc_pct, b.capacity_cycles, b.battery_r_samples};
  std::printf(
      "%s: capacity %.1f Ah (%d swings; truth 160), R %.2f mOhm (%d samples; truth %.2f), "
      "SoC counted %.1f %% / true %.1f %% (%.0f s wall, %.0f s cpu)\n",
      p.name, out.capacityAh, out.cycles, out.rMohm, out.rSamples, kTrueRmohm, out.socPct, out.trueSocPct,
      res.wallS, double(std::clock() - c0) / CLOCKS_PER_SEC);
  const TimeNs t0 = res.rows.front().telemetry.now - fromSec(res.rows.front().t_s);
  for (const Event& e : res.events)
    if (e.code == EventCode::CapacityMeasured) {
      const SimRow* row = at(res, toSec(e.t - t0));
      std::printf("  %.1f h: swing %.1f Ah over %.1f %% (true SoC there %.1f %%)\n", toSec(e.t - t0) / 3600.0,
                  e.a, e.b, row ? row->plant.soc_pct : -1.0);
    }
  if (!(std::fabs(out.capacityAh - 160.0) <= 16.0) || out.rSamples < 5)
    std::printf("%s", trace(res, 3600).c_str());
  return out;
}

void expectHealth(const Outcome& o) {
  EXPECT_GE(o.cycles, 2);
  EXPECT_NEAR(o.capacityAh, 160.0, 16.0);
  EXPECT_NEAR(o.rMohm, kTrueRmohm, 0.25 * kTrueRmohm);
}

TEST(HealthFromOrdinaryUse, MorningRunsToTheAbsorptionTimeoutEveningsAndFridgeNights) {
  Pattern p{"5 h engine mornings, 15 A evenings, 5 A fridge half the time",
            70.0,
            5.0,
            0.5,
            1800.0,
            0.0,
            11,
            {{{{0.0, 5.0}}, 1.0, 15.0, 4.0, 0.3}, {{{0.0, 5.0}}, 1.0, 15.0, 4.0, 0.3}},
            20.0};
  expectHealth(run(p));
}

TEST(HealthFromOrdinaryUse, AQuietDayAShortHopThatStopsLongBeforeTheTailThenAPassage) {
  // A day at anchor, a 1.5 h hop at 07:00 that stops early in absorption,
  // then a 4 h passage; a 15 A evening for 3 h, a 4 A compressor 30 % of
  // every 20 min. A 1.5 h run puts back about a third of the bank, so the
  // hop's night and midday points are under 30 % apart: the quiet day gives
  // one swing, the passage the second.
  Pattern p{
      "a quiet day, a 1.5 h hop, a 4 h passage, 15 A evenings, 4 A fridge 30 % of 20 min",
      90.0,
      4.0,
      0.3,
      1200.0,
      0.0,
      23,
      {{{}, 0.5, 15.0, 3.0, 0.3}, {{{0.0, 1.5}}, 0.5, 15.0, 3.0, 0.3}, {{{0.0, 4.0}}, 0.5, 15.0, 3.0, 0.3}},
      9.0};
  expectHealth(run(p));
}

TEST(HealthFromOrdinaryUse, AnAnchorageDrainedThenOneLongRun) {
  // A day and a night at anchor on the bank alone, then one long run that
  // stops in absorption, then a second night; a 3.5 A compressor 40 % of
  // every 40 min, 8 A evenings.
  Pattern p{"a day at anchor, one 6 h run, 8 A evenings, 3.5 A fridge 40 % of 40 min",
            95.0,
            3.5,
            0.4,
            2400.0,
            0.0,
            37,
            {{{}, 1.0, 8.0, 4.0, 0.4}, {{{1.0, 6.0}}, 1.0, 8.0, 4.0, 0.4}, {{}, 1.0, 10.0, 3.0, 0.4}},
            12.0};
  expectHealth(run(p));
}

TEST(HealthFromOrdinaryUse, SolarDaysWithAnEveningRunAndAFridgeThatCyclesFast) {
  // 20 A of solar at noon; the engine runs 2 h in the morning on the first
  // day and 1 h at 17:00 on the second; a 4.5 A fridge half of every 15 min.
  Pattern p{
      "solar 20 A, 2 h then 1 h runs, 12 A evenings, 4.5 A fridge half of 15 min",
      60.0,
      4.5,
      0.5,
      900.0,
      20.0,
      53,
      {{{{0.0, 2.0}}, 2.0, 12.0, 4.0, 0.5}, {{{10.0, 1.0}}, 2.0, 12.0, 4.0, 0.5}, {{}, 2.0, 12.0, 4.0, 0.5}},
      8.0};
  expectHealth(run(p));
}

}  // namespace
}  // namespace xr::sim::test
