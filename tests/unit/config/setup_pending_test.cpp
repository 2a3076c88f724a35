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

}  // namespace
}  // namespace xr
