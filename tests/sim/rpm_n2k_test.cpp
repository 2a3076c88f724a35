// RpmSource = n2k (docs/integrations.md): engine speed from a simulated engine ECU on
// the simulated NMEA 2000 bus (127488) drives the RPM tables through the
// daemon's CAN service; a silent ECU is treated like a lost tach (0 rpm:
// REASON_RPM_LOW, field off) even though the engine, and its W terminal,
// still turn.
#include <gtest/gtest.h>

#include "closed_loop.h"

namespace xr::sim::test {
namespace {

constexpr const char* kScenario = R"(name = "engine speed from N2K"
duration_s = 120
seed = 27
[config]
BatteryCapacity_Ah = 400
BulkVoltage = 14.4
AbsorptionVoltage = 14.4
rpmCapCurrentTable = [0, 20, 30, 40, 50, 60, 70, 80, 90, 100]
[battery]
chemistry = "lifepo4"
capacity_ah = 400
soc_pct = 30
[alternator]
rated_a = 150
[engine]
rpm = 1100
ecu = true
[loads]
house_a = 5
[[events]]
at_s = 30
rpm = 2100
[[events]]
at_s = 60
ecu = "silent"
[[events]]
at_s = 90
ecu = "talking"
)";

SimRunResult run(const std::string& source) {
  SimRunOptions o;
  o.scenario = parseScenario(kScenario, "rpm_n2k.toml");
  o.settings.can.n2k_interface = "can1";  // --sim puts it on the simulated N2K bus
  o.settings.can.RpmSource = source;
  o.telemetryRateHz = 10.0;
  SimRunner r(o);
  SimRunResult res = r.run();
  EXPECT_EQ(res.inaProtocolErrors, 0u);
  EXPECT_FALSE(res.finalFieldEnable);
  return res;
}

TEST(RpmFromN2k, TheEcuSpeedDrivesTheRpmTables) {
  const SimRunResult r = run("n2k");
  // The telemetry RPM is the ECU's (0.25 rpm resolution), within a second.
  EXPECT_TRUE(all(
      r, [](const SimRow& w) { return std::abs(w.telemetry.rpm - 1100.0) <= 0.25; }, 1.0, 30.0))
      << trace(r, 5);
  EXPECT_TRUE(all(
      r, [](const SimRow& w) { return std::abs(w.telemetry.rpm - 2100.0) <= 0.25; }, 31.0, 60.0))
      << trace(r, 5);
  // The cap table at 1100 rpm is 30 A, at 2100 rpm 50 A: the alternator
  // current follows the table (bulk, the bank takes all it gets).
  EXPECT_NEAR(maxOf(
                  r, [](const SimRow& w) { return w.telemetry.alt_a; }, 20.0, 30.0),
              30.0, 3.0)
      << trace(r, 5);
  EXPECT_NEAR(maxOf(
                  r, [](const SimRow& w) { return w.telemetry.alt_a; }, 50.0, 60.0),
              50.0, 3.0)
      << trace(r, 5);
}

TEST(RpmFromN2k, ASilentEcuIsALostTach) {
  const SimRunResult r = run("n2k");
  // Silent from 60 s: stale after fresh::kEngineRpmMaxAgeS (1 s), then
  // 0 rpm, below MinRPMForField: the field is cut as with no tach pulses.
  const double zero = firstTime(
      r, [](const SimRow& w) { return w.telemetry.rpm == 0.0; }, 60.0);
  ASSERT_GE(zero, 60.0) << trace(r, 5);
  EXPECT_LE(zero, 61.2) << trace(r, 5);
  EXPECT_TRUE(all(
      r,
      [](const SimRow& w) {
        return w.telemetry.reason == Reason::REASON_RPM_LOW && !w.telemetry.field_enable;
      },
      zero + 0.5, 90.0))
      << trace(r, 5);
  EXPECT_TRUE(all(
      r, [](const SimRow& w) { return w.plant.alt_a < 1.0; }, zero + 2.0, 90.0))
      << trace(r, 5);
  // The ECU talks again: the RPM and the charge come back.
  EXPECT_TRUE(all(
      r, [](const SimRow& w) { return std::abs(w.telemetry.rpm - 2100.0) <= 0.25; }, 91.0, 120.0))
      << trace(r, 5);
  EXPECT_GT(maxOf(
                r, [](const SimRow& w) { return w.telemetry.alt_a; }, 100.0, 120.0),
            40.0)
      << trace(r, 5);
}

TEST(RpmFromN2k, WithTheTachTheEcuIsNotListenedTo) {
  // The same run with RpmSource = tach: the ECU going silent changes nothing.
  const SimRunResult r = run("tach");
  EXPECT_TRUE(all(
      r, [](const SimRow& w) { return w.telemetry.field_enable; }, 62.0, 90.0))
      << trace(r, 5);
  EXPECT_GT(maxOf(
                r, [](const SimRow& w) { return w.telemetry.alt_a; }, 62.0, 90.0),
            40.0)
      << trace(r, 5);
}

}  // namespace
}  // namespace xr::sim::test
