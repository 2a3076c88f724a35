// The SoC an owner sees at first start (docs/batteries.md "State of charge at
// first start"), through the real drivers on the simulated bank: a 35 %
// AGM bank at rest is estimated within 10 points from its voltage; a
// LiFePO4 bank says "unknown" and gives no number.
#include "closed_loop.h"

namespace xr::sim::test {
namespace {

std::string firstStart(const char* profile, const char* chemistry) {
  return std::string(R"(
duration_s = 120
seed = 31
[config]
BatteryProfile = ")") + profile + R"("
[battery]
chemistry = ")" + chemistry + R"("
capacity_ah = 200
soc_pct = 35
[engine]
rpm = 0
[loads]
house_a = 2
)";
}

TEST(SocAtFirstStart, A35PercentAgmBankAtRestShowsAnEstimateWithinTenPoints) {
  const auto r = runText(firstStart("agm", "agm"));
  const SimRow* last = at(r, 110);
  ASSERT_NE(last, nullptr);
  EXPECT_EQ(last->telemetry.battery.socSource, SocSource::OcvEstimate) << trace(r, 10);
  EXPECT_NEAR(last->telemetry.battery.SOC_percent, 35.0, 10.0) << trace(r, 10);
  EXPECT_FALSE(last->telemetry.battery.socKnown);
}

TEST(SocAtFirstStart, ALiFePO4BankAtFirstStartIsUnknown) {
  const auto r = runText(firstStart("lifepo4", "lifepo4"));
  EXPECT_TRUE(all(r, [](const SimRow& x) { return x.telemetry.battery.socSource == SocSource::Unknown; }))
      << trace(r, 10);
}

}  // namespace
}  // namespace xr::sim::test
