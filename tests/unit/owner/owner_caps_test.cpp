// The caps' telemetry from a running Regulator: what the owner model reads
// is what the control law applied (docs/dashboard.md "Owner model").
#include <gtest/gtest.h>

#include "owner/owner_model.h"
#include "reg_rig.h"

namespace xr {
namespace {

Params lifepo4NoProbe() {
  Params p;
  p.BatteryTempRequired = true;
  p.BatteryCapacity_Ah = 280.0;
  return p;
}

TEST(OwnerCaps, LiFePO4WithoutAProbeReportsTheC10CapAndTheLawHoldsIt) {
  test::RegRig r(lifepo4NoProbe());
  r.run(20.0);
  const Telemetry& t = r.out->telemetry;
  ASSERT_EQ(t.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  EXPECT_EQ(t.caps.batteryTempCause, BatteryTempCap::NO_PROBE);
  EXPECT_NEAR(t.caps.batteryTempA, 28.0, 1e-9);
  EXPECT_LE(t.caps.commandA, t.caps.batteryCapAltA + 1e-9);
  const auto m = owner::ownerModel(t);
  ASSERT_FALSE(m.limits.empty());
  EXPECT_EQ(m.limits.front().id, "battery_temp_required");
  EXPECT_DOUBLE_EQ(m.limits.front().amps, 28.0);
}

TEST(OwnerCaps, WithoutTheRuleNoBatteryTemperatureCapIsReported) {
  Params p = lifepo4NoProbe();
  p.BatteryTempRequired = false;
  test::RegRig r(p);
  r.run(5.0);
  EXPECT_EQ(r.out->telemetry.caps.batteryTempCause, BatteryTempCap::NONE);
  EXPECT_TRUE(std::isnan(r.out->telemetry.caps.batteryTempA));
}

TEST(OwnerCaps, TheRpmTableAtLowSpeedIsReportedAsTheEngineSpeedLimit) {
  test::RegRig r;
  r.rpm = 400.0;  // the default table ramps from 0 at 100 rpm to its top at 600
  r.run(5.0);
  const CommandCaps& c = r.out->telemetry.caps;
  ASSERT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  EXPECT_LT(c.rpmTableA, c.rpmTableTopA);
  EXPECT_DOUBLE_EQ(c.commandA, std::min(c.rpmTableA, c.ratingA));
}

}  // namespace
}  // namespace xr
