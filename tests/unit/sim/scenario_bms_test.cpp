// The simulated BMS's scenario keys (docs/integrations.md): [bms] and the bms_* events,
// with file:line: errors on bad values (the daemon exits 64 on them).
#include <gtest/gtest.h>

#include "drivers/sim/scenario.h"

namespace xr::sim {
namespace {

std::string errorOf(std::string_view text) {
  try {
    parseScenario(text, "b.toml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioBms, ParsesTheTableAndTheEvents) {
  const Scenario s = parseScenario(R"(name = "x"
[bms]
can = true
protocol = "pylontech"
cvl_v = 14.0
ccl_max_a = 150
open_after_s = 2
[[events]]
at_s = 10
bms_ccl_a = 30
bms_warn = "high_voltage"
[[events]]
at_s = 20
bms_can = "silent"
bms_cvl_v = 13.9
[[events]]
at_s = 30
bms_can = "short_frames"
bms_ccl_a = "auto"
bms_warn = "none"
)",
                                   "b.toml");
  EXPECT_TRUE(s.bms.can);
  EXPECT_EQ(s.bms.protocol, "pylontech");
  EXPECT_DOUBLE_EQ(s.bms.cvl_v, 14.0);
  EXPECT_DOUBLE_EQ(s.bms.ccl_max_a, 150.0);
  EXPECT_DOUBLE_EQ(s.bms.open_after_s, 2.0);
  ASSERT_EQ(s.events.size(), 3u);
  EXPECT_EQ(*s.events[0].bms_ccl_a, 30.0);
  EXPECT_TRUE(*s.events[0].bms_warn);
  EXPECT_EQ(*s.events[1].bms_can, BmsCanMode::Silent);
  EXPECT_EQ(*s.events[1].bms_cvl_v, 13.9);
  EXPECT_EQ(*s.events[2].bms_can, BmsCanMode::ShortFrames);
  EXPECT_LT(*s.events[2].bms_ccl_a, 0.0);  // auto
  EXPECT_FALSE(*s.events[2].bms_warn);
  EXPECT_TRUE(s.events[2].touchesSimCan());
}

TEST(ScenarioBms, RecWithACellSpread) {
  const Scenario s =
      parseScenario("name = \"x\"\n[bms]\ncan = true\nprotocol = \"rec\"\ncell_spread_v = 0.08\n", "b.toml");
  EXPECT_EQ(s.bms.protocol, "rec");
  EXPECT_DOUBLE_EQ(s.bms.cell_spread_v, 0.08);
}

TEST(ScenarioBms, NoBmsByDefault) {
  const Scenario s = parseScenario("name = \"x\"\n", "b.toml");
  EXPECT_FALSE(s.bms.can);
}

TEST(ScenarioBms, BadValuesHaveFileAndLine) {
  auto e = errorOf("[bms]\ncan = true\nprotocol = \"jk\"\n");
  EXPECT_EQ(e.rfind("b.toml:3:", 0), 0u) << e;
  EXPECT_NE(e.find("protocol"), std::string::npos) << e;
  EXPECT_NE(e.find("\"rec\""), std::string::npos) << e;  // lists the valid ones
  e = errorOf("[bms]\ncan = true\ncell_spread_v = 0.6\n");
  EXPECT_EQ(e.rfind("b.toml:3:", 0), 0u) << e;
  e = errorOf("[bms]\ncan = \"yes\"\n");
  EXPECT_EQ(e.rfind("b.toml:2:", 0), 0u) << e;
  e = errorOf("[bms]\ncan = true\ncolour = 1\n");
  EXPECT_EQ(e.rfind("b.toml:3:", 0), 0u) << e;
  e = errorOf("[bms]\ncan = true\n[[events]]\nat_s = 1\nbms_can = \"shouting\"\n");
  EXPECT_EQ(e.rfind("b.toml:5:", 0), 0u) << e;
  e = errorOf("[bms]\ncan = true\n[[events]]\nat_s = 1\nbms_ccl_a = -3\n");
  EXPECT_EQ(e.rfind("b.toml:5:", 0), 0u) << e;
  e = errorOf("[bms]\ncan = true\n[[events]]\nat_s = 1\nbms_ccl_a = 7000\n");
  EXPECT_EQ(e.rfind("b.toml:5:", 0), 0u) << e;
  e = errorOf("[bms]\ncan = true\n[[events]]\nat_s = 1\nbms_cvl_v = \"high\"\n");
  EXPECT_EQ(e.rfind("b.toml:5:", 0), 0u) << e;
  e = errorOf("[bms]\ncan = true\n[[events]]\nat_s = 1\nbms_warn = \"low_voltage\"\n");
  EXPECT_EQ(e.rfind("b.toml:5:", 0), 0u) << e;
}

// The BMS follows the bank unless told otherwise: 0 cells and 0 V CVL mean
// "the [battery]'s cells, 3.55 V each" (the rig resolves them).
TEST(ScenarioBms, CellsAndCvlFollowTheBankUnlessSet) {
  const Scenario dflt = parseScenario("name = \"x\"\n[bms]\ncan = true\n", "b.toml");
  EXPECT_EQ(dflt.bms.cells, 0);
  EXPECT_DOUBLE_EQ(dflt.bms.cvl_v, 0.0);
  const Scenario four = parseScenario("name = \"x\"\n[bms]\ncan = true\ncells = 4\n", "b.toml");
  EXPECT_EQ(four.bms.cells, 4);
  auto e = errorOf("[bms]\ncan = true\ncells = 4.5\n");
  EXPECT_EQ(e.rfind("b.toml:3:", 0), 0u) << e;
  e = errorOf("[bms]\ncan = true\ncells = 0\n");
  EXPECT_EQ(e.rfind("b.toml:3:", 0), 0u) << e;
}

TEST(ScenarioBms, EventsNeedASimulatedBms) {
  // The events may come before the [bms] table in the file: checked after.
  auto e = errorOf("[[events]]\nat_s = 1\nbms_ccl_a = 30\n");
  EXPECT_EQ(e.rfind("b.toml:1:", 0), 0u) << e;
  EXPECT_NE(e.find("[bms] can = true"), std::string::npos) << e;
  EXPECT_EQ(errorOf("[[events]]\nat_s = 1\nbms_ccl_a = 30\n[bms]\ncan = true\n"), "");
}

}  // namespace
}  // namespace xr::sim
