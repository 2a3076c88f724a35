// Battery profiles and battery temperature on the simulator (docs/batteries.md): the
// real drivers read a second simulated DS18B20 on the bank; the scenarios of
// scenarios/ drive its temperature.
#include <gtest/gtest.h>

#include <filesystem>

#include "closed_loop.h"

namespace xr::sim::test {
namespace {

SimRunResult runFile(const char* name) {
  SimRunOptions o;
  o.scenario = loadScenario(std::filesystem::path(XR_SOURCE_DIR) / "scenarios" / name);
  o.telemetryRateHz = 2.0;
  SimRunner r(o);
  SimRunResult res = r.run();
  EXPECT_EQ(res.inaProtocolErrors, 0u);
  EXPECT_EQ(res.adsProtocolErrors, 0u);
  EXPECT_FALSE(res.finalFieldEnable);
  return res;
}

int countEvents(const SimRunResult& r, EventCode code, Reason reason) {
  int n = 0;
  for (const auto& e : r.events) n += e.code == code && e.reason == reason;
  return n;
}

double meanOf(const SimRunResult& r, const std::function<double(const SimRow&)>& f,
              const std::function<bool(const SimRow&)>& when) {
  double s = 0.0;
  int n = 0;
  for (const auto& row : r.rows)
    if (when(row)) {
      s += f(row);
      ++n;
    }
  return n ? s / n : kNoValue;
}

TEST(BatteryTempClosedLoop, ColdLifepoGetsNoChargeUntilPastZeroThenRamps) {
  const SimRunResult r = runFile("lfp-cold-start.toml");
  // -5 then -2 degC: no charge current at all (alternator <= 1 A, plant truth).
  EXPECT_TRUE(all(
      r, [](const SimRow& x) { return x.plant.alt_a <= 1.0; }, 0.0, 899.0))
      << trace(r, 60);
  EXPECT_TRUE(all(
      r, [](const SimRow& x) { return x.telemetry.reason == Reason::REASON_BATTERY_COLD; }, 2.0, 899.0));
  // The battery sensor is read through the real w1 driver.
  EXPECT_NEAR(at(r, 300.0)->telemetry.battery_temp_c, -5.0, 0.1);
  // One trip, no buzzer: no alarm storm. The cold hold itself sounds nothing;
  // 15 min of it with the engine running is one ChargingHeld warning and its
  // alarm row (docs/protections.md "Never silently not charging").
  EXPECT_EQ(countEvents(r, EventCode::ProtectionTrip, Reason::REASON_BATTERY_COLD), 1);
  EXPECT_TRUE(all(
      r, [](const SimRow& x) { return !x.telemetry.alarm; }, 0.0, 899.0));
  int held = 0;
  for (const auto& e : r.events) held += e.code == EventCode::ChargingHeld && e.level == EventLevel::Warning;
  EXPECT_LE(held, 1);
  if (held == 0) {
    EXPECT_TRUE(all(r, [](const SimRow& x) { return !x.telemetry.alarm; }));
  }
  // 1 degC: charging again, the battery current capped at 20 % of the 0.5 C
  // profile maximum (100 A for 200 Ah), the 5 A house load served on top
  // (docs/batteries.md "Temperature rules"); 6 degC and up: the cap is gone.
  const double resumed = firstTime(
      r, [](const SimRow& x) { return x.plant.alt_a > 2.0; }, 900.0);
  ASSERT_GT(resumed, 900.0) << trace(r, 60);
  EXPECT_LT(resumed, 1000.0);
  EXPECT_LE(maxOf(
                r, [](const SimRow& x) { return x.plant.battery_a; }, 910.0, 1199.0),
            20.0 + 1.0);
  EXPECT_LE(maxOf(
                r, [](const SimRow& x) { return x.telemetry.target_a; }, 905.0, 1199.0),
            20.0 + 5.0 + 1.0);
  EXPECT_LE(maxOf(
                r, [](const SimRow& x) { return x.telemetry.target_a; }, 1205.0, 1499.0),
            50.0 + 1e-6);
  // 6 degC: only the RPM cap table (50 A by default) limits the command.
  EXPECT_GT(maxOf(
                r, [](const SimRow& x) { return x.telemetry.target_a; }, 1850.0),
            49.0);
  const double at1C = maxOf(
      r, [](const SimRow& x) { return x.plant.alt_a; }, 950.0, 1199.0);
  const double at6C = maxOf(
      r, [](const SimRow& x) { return x.plant.alt_a; }, 1850.0, 2399.0);
  EXPECT_GT(at6C, at1C + 10.0) << trace(r, 60);
}

TEST(BatteryTempClosedLoop, HotAgmAbsorbsAtTheCompensatedVoltage) {
  const SimRunResult r = runFile("agm-hot.toml");
  // 14.4 V + (-4 mV x 6 cells) x (T - 25 degC): 14.04 V at 40 degC; the bank
  // warms a little from its own losses and the target follows the sensor.
  auto compensated = [](const SimRow& x) { return 14.4 - 0.024 * (x.telemetry.battery_temp_c - 25.0); };
  const double abs0 =
      firstTime(r, [](const SimRow& x) { return x.telemetry.stage == ChargeStage::ABSORPTION; });
  ASSERT_GT(abs0, 0.0) << trace(r, 60);
  EXPECT_NEAR(at(r, abs0 + 1.0)->telemetry.battery_temp_c, 40.0, 0.5);
  EXPECT_TRUE(all(
      r, [&](const SimRow& x) { return std::abs(x.telemetry.target_v - compensated(x)) < 1e-6; }, abs0,
      3600.0));
  auto inAbsorption = [&](const SimRow& x) {
    return x.t_s > abs0 + 120.0 && x.telemetry.stage == ChargeStage::ABSORPTION;
  };
  const double err = meanOf(
      r, [&](const SimRow& x) { return x.plant.battery_v - compensated(x); }, inAbsorption);
  EXPECT_NEAR(err, 0.0, 0.020) << trace(r, 60);
  EXPECT_LT(maxOf(
                r, [](const SimRow& x) { return x.plant.battery_v; }, abs0 + 120.0),
            14.04 + 0.10);
}

TEST(BatteryTempClosedLoop, HotBatteryStopsChargingAndResumesWithHysteresis) {
  const SimRunResult r = runFile("battery-hot-stop.toml");
  // 45 degC: charging.
  EXPECT_GT(maxOf(
                r, [](const SimRow& x) { return x.plant.alt_a; }, 100.0, 299.0),
            10.0)
      << trace(r, 30);
  // 52 degC: stopped; 48 degC is still within the 3 degC hysteresis of 50.
  EXPECT_TRUE(all(
      r, [](const SimRow& x) { return x.telemetry.reason == Reason::REASON_BATTERY_HOT; }, 302.0, 899.0))
      << trace(r, 30);
  EXPECT_TRUE(all(
      r, [](const SimRow& x) { return x.plant.alt_a <= 1.0; }, 320.0, 899.0))
      << trace(r, 30);
  // 46.5 degC (<= 47): resumes.
  const double resumed = firstTime(
      r, [](const SimRow& x) { return x.plant.alt_a > 5.0; }, 900.0);
  EXPECT_GT(resumed, 900.0);
  EXPECT_LT(resumed, 960.0) << trace(r, 30);
  EXPECT_EQ(countEvents(r, EventCode::ProtectionTrip, Reason::REASON_BATTERY_HOT), 1);
  EXPECT_EQ(countEvents(r, EventCode::ProtectionClear, Reason::REASON_BATTERY_HOT), 1);
}

TEST(BatteryTempClosedLoop, TwentyFourVoltLifepoBankFromTheSameProfile) {
  const SimRunResult r = runFile("lfp-24v-profile.toml");
  EXPECT_NEAR(at(r, 10.0)->telemetry.target_v, 28.4, 1e-6);
  EXPECT_LT(maxOf(r, [](const SimRow& x) { return x.plant.battery_v; }), 28.4 + 0.3) << trace(r, 120);
  EXPECT_GT(r.finalTruth.soc_pct, 60.0 + 5.0) << trace(r, 120);
  EXPECT_TRUE(all(
      r, [](const SimRow& x) { return !x.telemetry.alarm; }, 5.0))
      << trace(r, 120);
}

}  // namespace
}  // namespace xr::sim::test
