#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "config/overrides.h"

namespace xr {
namespace {

using ::testing::HasSubstr;

TEST(FlatOverrides, AppliesScenarioConfigTable) {
  const auto doc = toml::parse(R"(
[config]
BulkVoltage = 14.4
TargetVoltageMode = 1
rpmCapCurrentTable = [0, 30, 30, 30, 30, 30, 30, 30, 30, 30]
)");
  Params p;
  const auto errs = applyFlatOverrides(p, *doc["config"].as_table(), "s.toml");
  EXPECT_TRUE(errs.empty());
  EXPECT_DOUBLE_EQ(p.BulkVoltage, 14.4);
  EXPECT_TRUE(p.TargetVoltageMode);
  EXPECT_DOUBLE_EQ(p.rpmCapCurrentTable[5], 30.0);
}

TEST(FlatOverrides, AnyErrorLeavesParamsUntouchedAndNamesTheLine) {
  const auto doc = toml::parse("BulkVoltage = 14.4\nBulkVoltge = 14.4\nMaxDuty = 120\n", std::string_view("s.toml"));
  Params p;
  const auto errs = applyFlatOverrides(p, doc, "s.toml");
  ASSERT_EQ(errs.size(), 2u);
  EXPECT_EQ(p, Params{});
  std::vector<std::string> text;
  for (const auto& e : errs) text.push_back(e.toString());
  EXPECT_THAT(text, ::testing::Contains(HasSubstr("s.toml:2:1: BulkVoltge: unknown parameter (did you mean BulkVoltage?)")));
  EXPECT_THAT(text, ::testing::Contains(HasSubstr("s.toml:3:1: MaxDuty: 120 is out of range: allowed 0 to 100 %")));
}

TEST(FlatOverrides, InlineSetTableIsCheckedForConsistency) {
  const auto doc = toml::parse("set = { FloatVoltage = 14.6 }");
  Params p;
  const auto errs = applyFlatOverrides(p, *doc["set"].as_table());
  ASSERT_EQ(errs.size(), 1u);
  EXPECT_THAT(errs[0].toString(), HasSubstr("FloatVoltage"));
  EXPECT_EQ(p, Params{});
}

}  // namespace
}  // namespace xr
