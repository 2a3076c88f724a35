// "Not set up" (docs/configuration.md "Not set up"): until a battery type is
// named, the charge voltages and the battery-temperature window are lowered
// to what every common chemistry tolerates, per bank size, and the set stays
// one the set checks accept.
#include "config/setup_pending.h"

#include <gtest/gtest.h>

#include "config/battery_profiles.h"
#include "config/config.h"
#include "config/param_sources.h"

namespace xr {
namespace {

TEST(SetupPending, LowersTheChargeVoltagesOfATwelveVoltBankToFourteenVolts) {
  NameSet capped;
  const Params p = withSetupPendingLimits(Params{}, capped);  // catalogue: 14.5 / 14.4 / 13.5 V
  EXPECT_DOUBLE_EQ(p.BulkVoltage, 14.0);
  EXPECT_DOUBLE_EQ(p.AbsorptionVoltage, 14.0);
  EXPECT_DOUBLE_EQ(p.FloatVoltage, 13.4);
  EXPECT_TRUE(capped.count("BulkVoltage") && capped.count("FloatVoltage"));
  EXPECT_TRUE(checkConsistency(p).empty()) << checkConsistency(p).front().message;
}

TEST(SetupPending, ScalesWithTheBankClassOfBulkVoltage) {
  Params in;
  in.BulkVoltage = 28.8;
  in.AbsorptionVoltage = 28.6;
  in.FloatVoltage = 27.0;
  NameSet capped;
  const Params p = withSetupPendingLimits(in, capped);
  EXPECT_DOUBLE_EQ(p.BulkVoltage, 28.0);
  EXPECT_DOUBLE_EQ(p.AbsorptionVoltage, 28.0);
  EXPECT_DOUBLE_EQ(p.FloatVoltage, 26.8);
  EXPECT_NE(setupPendingLimitsText(in).find("at most 28 V, float 26.8 V"), std::string::npos);
}

TEST(SetupPending, LeavesAValueAlreadyInsideTheLimitAsItIs) {
  Params in;
  in.BulkVoltage = 13.9;  // below 14.0: kept
  in.AbsorptionVoltage = 13.9;
  in.FloatVoltage = 13.4;  // at the limit: kept, not named
  NameSet capped;
  const Params p = withSetupPendingLimits(in, capped);
  EXPECT_DOUBLE_EQ(p.BulkVoltage, 13.9);
  EXPECT_FALSE(capped.count("BulkVoltage"));
  EXPECT_FALSE(capped.count("FloatVoltage"));
}

TEST(SetupPending, NarrowsTheBatteryTemperatureWindowAndStopsCompensation) {
  Params in;
  in.TempCompMvPerCellC = -4.0;  // lead-acid compensation raises the voltage in the cold
  NameSet capped;
  const Params p = withSetupPendingLimits(in, capped);
  EXPECT_DOUBLE_EQ(p.ChargeMinTempC, 5.0);
  EXPECT_DOUBLE_EQ(p.ChargeFullCurrentTempC, 5.0);
  EXPECT_DOUBLE_EQ(p.ChargeMaxTempC, 45.0);
  EXPECT_DOUBLE_EQ(p.TempCompMvPerCellC, 0.0);
  EXPECT_TRUE(checkConsistency(p).empty());
}

TEST(SetupPending, TheBatteryIsChosenByTheFileOrTheDashboard) {
  EXPECT_FALSE(batteryChosen({}, {}));
  EXPECT_FALSE(batteryChosen({"BulkVoltage", "BatteryCells"}, {"FloatVoltage"}));
  EXPECT_TRUE(batteryChosen({"BatteryProfile"}, {}));
  EXPECT_TRUE(batteryChosen({}, {"BatteryProfile"}));
}

TEST(SetupPending, RunningParamsLowerOnlyUntilSetUpAndNameTheLoweredValues) {
  ParamOrigins o;
  Params run = runningParams(Params{}, o);
  EXPECT_DOUBLE_EQ(run.BulkVoltage, 14.0);
  EXPECT_EQ(o.of("BulkVoltage"), ParamSource::SetupPending);
  EXPECT_EQ(toString(o.of("BulkVoltage")), "not set up");
  o.file.insert("BatteryProfile");
  run = runningParams(Params{}, o);
  EXPECT_DOUBLE_EQ(run.BulkVoltage, 14.5);
  EXPECT_EQ(o.of("BulkVoltage"), ParamSource::Default);
  ParamOrigins scenario;
  scenario.assumeSetUp = true;
  EXPECT_DOUBLE_EQ(runningParams(Params{}, scenario).BulkVoltage, 14.5);
}

// The reproducer: TargetVoltageSetpoint 14.8 (and 14.9 after BulkVoltage
// 14.6) ran while not set up. Every voltage target is lowered now, and the
// core gets the ceiling to clamp what it computes.
TEST(SetupPending, LowersEveryVoltageTargetAndHandsTheCeilingToTheCore) {
  Params in;
  in.BulkVoltage = 14.6;
  in.TargetVoltageMode = 1;
  in.TargetVoltageSetpoint = 14.9;
  in.ChargedVoltage = 14.2;
  in.RebulkVoltage = 13.45;  // under the file's float 13.5, over the lowered 13.4
  NameSet capped;
  const Params p = withSetupPendingLimits(in, capped);
  EXPECT_DOUBLE_EQ(p.TargetVoltageSetpoint, 14.0);
  EXPECT_DOUBLE_EQ(p.ChargedVoltage, 14.0);
  EXPECT_LT(p.RebulkVoltage, p.FloatVoltage);
  EXPECT_DOUBLE_EQ(p.SetupCeilingV, 14.0);
  EXPECT_TRUE(capped.count("TargetVoltageSetpoint") && capped.count("ChargedVoltage") &&
              capped.count("RebulkVoltage"));
  EXPECT_TRUE(checkConsistency(p).empty()) << checkConsistency(p).front().message;
  // Set up: no ceiling for the core.
  ParamOrigins o;
  o.file.insert("BatteryProfile");
  EXPECT_DOUBLE_EQ(runningParams(in, o).SetupCeilingV, 0.0);
  EXPECT_DOUBLE_EQ(runningParams(in, o).TargetVoltageSetpoint, 14.9);
}

TEST(SetupPending, TargetsAreCheckedAgainstTheLoweredValuesAtTheirThreshold) {
  Params p;  // a 12 V bank: charge limit 14.0 V, float 13.4 V
  p.TargetVoltageSetpoint = 14.0;
  p.ChargedVoltage = 14.0;
  p.RebulkVoltage = 13.39;
  EXPECT_TRUE(checkSetupPendingTargets(p).empty());
  p.TargetVoltageSetpoint = 14.01;
  p.ChargedVoltage = 14.01;
  p.RebulkVoltage = 13.4;
  const auto e = checkSetupPendingTargets(p);
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0].key, "TargetVoltageSetpoint");
  EXPECT_NE(e[0].message.find("above the charge limit 14 V while not set up"), std::string::npos)
      << e[0].message;
  EXPECT_EQ(e[1].key, "ChargedVoltage");
  EXPECT_EQ(e[2].key, "RebulkVoltage");
  // A 24 V bank: twice the limits.
  Params b;
  b.BulkVoltage = 28.8;
  b.AbsorptionVoltage = 28.6;
  b.FloatVoltage = 27.0;
  b.RebulkVoltage = 25.8;
  b.ChargedVoltage = 27.6;
  b.TargetVoltageSetpoint = 28.0;
  EXPECT_TRUE(checkSetupPendingTargets(b).empty());
  b.TargetVoltageSetpoint = 28.1;
  ASSERT_EQ(checkSetupPendingTargets(b).size(), 1u);
}

}  // namespace
}  // namespace xr
