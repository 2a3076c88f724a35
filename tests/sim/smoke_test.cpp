#include <gtest/gtest.h>

#include <cstdio>

#include "drivers/sim/runner/sim_runner.h"

namespace xr::sim {
namespace {
TEST(SimSmoke, Runs) {
  SimRunOptions o;
  o.scenario = defaultScenario();
  o.durationS = 120;
  o.telemetryRateHz = 1;
  SimRunner r(o);
  auto res = r.run();
  for (const auto& row : res.rows)
    std::printf("%6.1f %-28s %-10s %-28s ibv=%.3f bv=%.3f bcur=%.2f alt=%.2f rpm=%.0f T=%.1f duty=%.1f en=%d | true V=%.3f A=%.2f T=%.1f soc=%.2f\n",
                row.t_s, std::string(toString(row.telemetry.mode)).c_str(), std::string(toString(row.telemetry.stage)).c_str(),
                std::string(toString(row.telemetry.reason)).c_str(), row.telemetry.ibv_v, row.telemetry.battery_v,
                row.telemetry.bcur_a, row.telemetry.alt_a, row.telemetry.rpm, row.telemetry.temp_f, row.telemetry.duty_pct,
                row.telemetry.field_enable, row.plant.battery_v, row.plant.alt_a, row.plant.alt_temp_f, row.plant.soc_pct);
  std::printf("ticks=%llu i2c=%llu fail=%llu inaErr=%llu adsErr=%llu wall=%.3f\n", (unsigned long long)res.ticks,
              (unsigned long long)res.i2cTransfers, (unsigned long long)res.i2cFailures,
              (unsigned long long)res.inaProtocolErrors, (unsigned long long)res.adsProtocolErrors, res.wallS);
  for (const auto& e : res.events) std::printf("event %s\n", describe(e).c_str());
  EXPECT_GT(res.ticks, 0u);
}
}  // namespace
}  // namespace xr::sim
