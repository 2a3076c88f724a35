#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "config/param_values.h"

namespace xr {
namespace {

using ::testing::HasSubstr;

TEST(ParamMap, HoldsEveryCatalogueEntry) {
  const ParamMap m = toParamMap(Params{});
  EXPECT_EQ(m.size(), catalogue().size());
  EXPECT_DOUBLE_EQ(std::get<double>(m.at("BulkVoltage")), 14.5);
  EXPECT_EQ(std::get<std::vector<double>>(m.at("rpmMinDutyTable")).size(), RPM_TABLE_SIZE);
}

TEST(ParamMap, OverridesListOnlyWhatDiffers) {
  Params p;
  EXPECT_TRUE(overridesFromDefaults(p).empty());
  p.BulkVoltage = 14.2;
  p.rpmCapCurrentTable[2] = 45;
  const ParamMap o = overridesFromDefaults(p);
  ASSERT_EQ(o.size(), 2u);
  EXPECT_DOUBLE_EQ(std::get<double>(o.at("BulkVoltage")), 14.2);
  EXPECT_DOUBLE_EQ(std::get<std::vector<double>>(o.at("rpmCapCurrentTable"))[2], 45.0);
}

TEST(ParamText, EveryDefaultRoundTripsThroughText) {
  const Params p;
  for (const auto& s : catalogue()) {
    const ParamValue v = getParamValue(p, s);
    const auto back = parseParamValue(formatParamValue(v));
    ASSERT_TRUE(back.has_value()) << s.name;
    EXPECT_EQ(*back, v) << s.name << " <- " << formatParamValue(v);
  }
}

TEST(ParamText, AwkwardNumbersRoundTripExactly) {
  for (double d : {0.1, 1.0 / 3.0, 14.55, -0.0, 1e-9, 123456789.125}) {
    const auto back = parseParamValue(formatParamValue(d));
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(std::get<double>(*back), d);
  }
  EXPECT_EQ(formatParamValue(14.5), "14.5");
  EXPECT_EQ(formatParamValue(std::vector<double>{1, 2.5}), "[1, 2.5]");
}

TEST(ParamText, GarbageIsRejected) {
  EXPECT_FALSE(parseParamValue("").has_value());
  EXPECT_FALSE(parseParamValue("abc").has_value());
  EXPECT_FALSE(parseParamValue("14.5V").has_value());
  EXPECT_FALSE(parseParamValue("[1, 2").has_value());
  EXPECT_FALSE(parseParamValue("[1,, 2]").has_value());
}

TEST(ValidatePatch, AppliesAWholeValidPatch) {
  const Params base;
  const PatchResult r = validatePatch(base, {{"FloatVoltage", 13.4}, {"UseFloat", 0.0}});
  ASSERT_TRUE(r.ok());
  EXPECT_DOUBLE_EQ(r.params->FloatVoltage, 13.4);
  EXPECT_FALSE(r.params->UseFloat);
  EXPECT_DOUBLE_EQ(r.params->BulkVoltage, base.BulkVoltage);
}

TEST(ValidatePatch, OneBadEntryRejectsThePatchAndListsEveryError) {
  const PatchResult r =
      validatePatch(Params{}, {{"FloatVoltage", 13.4}, {"BulkVoltage", 99.0}, {"MaxDutty", 90.0}});
  EXPECT_FALSE(r.ok());
  EXPECT_FALSE(r.params.has_value());
  ASSERT_EQ(r.errors.size(), 2u);
  EXPECT_EQ(r.errors[0].key, "BulkVoltage");
  EXPECT_THAT(r.errors[0].message, HasSubstr("99 is out of range: allowed 8 to 64 V"));
  EXPECT_EQ(r.errors[1].key, "MaxDutty");
  EXPECT_THAT(r.errors[1].message, HasSubstr("did you mean MaxDuty?"));
}

TEST(ValidatePatch, ChecksTheResultAsAWhole) {
  // Each value fits its own range, but together Float would sit above Bulk.
  const PatchResult r = validatePatch(Params{}, {{"BulkVoltage", 13.0}});
  EXPECT_FALSE(r.ok());
  ASSERT_FALSE(r.errors.empty());
  EXPECT_THAT(r.errors[0].toString(), HasSubstr("AbsorptionVoltage"));
  // Lowering all three together is fine.
  EXPECT_TRUE(validatePatch(Params{}, {{"BulkVoltage", 13.9},
                                       {"AbsorptionVoltage", 13.8},
                                       {"FloatVoltage", 13.4},
                                       {"TargetVoltageSetpoint", 13.5}})
                  .ok());
}

TEST(ValidatePatch, TableShapeAndScalarShapeAreChecked) {
  EXPECT_THAT(validatePatch(Params{}, {{"rpmCapCurrentTable", 50.0}}).errors.at(0).message,
              HasSubstr("expected a list of 10 numbers"));
  EXPECT_THAT(validatePatch(Params{}, {{"BulkVoltage", std::vector<double>{14.5}}}).errors.at(0).message,
              HasSubstr("expected a single number"));
  EXPECT_THAT(validatePatch(Params{}, {{"PidSampleDivisor", 2.5}}).errors.at(0).message,
              HasSubstr("not a whole number"));
}

TEST(ClosestName, SuggestsTyposOnly) {
  EXPECT_EQ(closestParamName("bulkvoltage"), "BulkVoltage");
  EXPECT_EQ(closestParamName("TempAlarmLo"), "TempAlarmLow");
  EXPECT_EQ(closestParamName("CompletelyUnrelatedThing"), "");
}

}  // namespace
}  // namespace xr
