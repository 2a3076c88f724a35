// Scenario files: the format of docs/simulator.md, file:line errors.
#include "drivers/sim/scenario.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace xr::sim {
namespace {

std::string errorOf(std::string_view text) {
  try {
    parseScenario(text, "t.toml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

// set_up = false: the boat as delivered, before its set-up page; a scenario's
// boat is otherwise set up; anything but a boolean is refused with its line.
TEST(Scenario, SetUpFalseIsTheBoatAsDelivered) {
  EXPECT_TRUE(parseScenario("name = \"a\"\n", "t.toml").set_up);
  EXPECT_FALSE(parseScenario("name = \"a\"\nset_up = false\n", "t.toml").set_up);
  EXPECT_NE(errorOf("set_up = 0\n").find("t.toml:1: 'set_up' must be true or false"), std::string::npos)
      << errorOf("set_up = 0\n");
}

TEST(Scenario, ParsesTheDesignExample) {
  const char* text = R"(name = "load dump in absorption"
duration_s = 1800
seed = 7
[config]
BulkVoltage = 14.4
[battery]
chemistry = "lifepo4"
capacity_ah = 400
soc_pct = 35
[alternator]
rated_a = 120
field_tau_s = 0.15
temp_f = 80
ambient_f = 95
[engine]
rpm = 1800
[loads]
house_a = 15
[[events]]
at_s = 600
house_a = 90
[[events]]
at_s = 900
fault = "ina228_nack"
[[events]]
at_s = 905
clear = "ina228_nack"
[[events]]
at_s = 1000
bms = "disconnect"
[[events]]
at_s = 1200
command = "limp_home"
[[events]]
at_s = 1300
set = { TargetVoltageMode = 1, TargetVoltageSetpoint = 13.6 }
[[events]]
at_s = 1400
command = "set_soc"
soc_pct = 50
[[events]]
at_s = 1500
fault = "alt_current_offset"
value = 3.5
)";
  const Scenario s = parseScenario(text, "x.toml");
  EXPECT_EQ(s.name, "load dump in absorption");
  EXPECT_EQ(s.duration_s, 1800);
  EXPECT_EQ(s.seed, 7u);
  ASSERT_EQ(s.config.size(), 1u);
  EXPECT_EQ(s.config[0].name, "BulkVoltage");
  EXPECT_EQ(s.plant.battery.chemistry, Chemistry::lifepo4);
  EXPECT_EQ(s.plant.battery.capacity_ah, 400);
  EXPECT_EQ(s.plant.alternator.ambient_f, 95);
  EXPECT_EQ(s.plant.rpm, 1800);
  EXPECT_EQ(s.plant.house_a, 15);
  ASSERT_EQ(s.events.size(), 8u);
  EXPECT_EQ(*s.events[0].house_a, 90);
  EXPECT_EQ(*s.events[1].fault, Fault::ina228_nack);
  EXPECT_EQ(*s.events[2].clear, Fault::ina228_nack);
  EXPECT_EQ(*s.events[3].bms_connected, false);
  EXPECT_EQ(s.events[4].command->type, CommandType::LimpHome);
  ASSERT_EQ(s.events[5].set.size(), 2u);
  EXPECT_EQ(s.events[6].command->type, CommandType::SetSoc);
  EXPECT_EQ(s.events[6].command->value, 50);
  EXPECT_EQ(s.events[7].value, 3.5);
  Params p;
  applyOverrides(p, s.config);
  EXPECT_EQ(p.BulkVoltage, 14.4);
}

TEST(Scenario, SyntaxErrorHasFileAndLine) {
  EXPECT_EQ(errorOf("name = \"x\"\nduration_s = = 3\n").rfind("t.toml:2:", 0), 0u);
}

// scenario_fuzz's first finding (tests/fuzz/regressions): a non-ASCII
// letter after a bare key reached undefined behaviour in toml++ 3.3.0; the
// loader refuses it before toml++ sees it (config/toml_text_guard.h).
TEST(Scenario, NonAsciiAfterABareKeyIsRefusedAtLineAndColumn) {
  const auto e = errorOf("name = \"x\"\n[battery]\ncapacity_\xC6\x97 = 400\n");
  EXPECT_EQ(e.rfind("t.toml:3:10: non-ASCII character outside a string", 0), 0u) << e;
  const std::filesystem::path kept =
      std::filesystem::path(XR_SOURCE_DIR) / "tests/fuzz/regressions/non-ascii-after-bare-key.toml";
  try {
    loadScenario(kept);
    ADD_FAILURE() << "the kept finding loaded";
  } catch (const ScenarioError& err) {
    EXPECT_NE(std::string(err.what()).find("non-ascii-after-bare-key.toml:4:10: non-ASCII"),
              std::string::npos)
        << err.what();
  }
  // In strings and comments: fine.
  EXPECT_EQ(errorOf("name = \"caf\xC3\xA9 \xC6\x97\" # \xC6\x97\n").find("non-ASCII"), std::string::npos);
}

TEST(Scenario, UnknownKeyHasLine) {
  const auto e = errorOf("name = \"x\"\n[battery]\nchemistry = \"agm\"\ncapacity = 100\n");
  EXPECT_EQ(e.rfind("t.toml:4:", 0), 0u) << e;
  EXPECT_NE(e.find("capacity"), std::string::npos);
  EXPECT_EQ(errorOf("bogus = 1\n").rfind("t.toml:1:", 0), 0u);
}

TEST(Scenario, UnknownFaultChemistryCommandParameter) {
  EXPECT_NE(errorOf("[[events]]\nat_s = 1\nfault = \"gremlins\"\n").find("t.toml:3: unknown fault"),
            std::string::npos);
  EXPECT_NE(errorOf("[battery]\nchemistry = \"nicd\"\n").find("t.toml:2:"), std::string::npos);
  EXPECT_NE(errorOf("[[events]]\nat_s = 1\ncommand = \"fly\"\n").find("t.toml:3:"), std::string::npos);
  EXPECT_NE(errorOf("[config]\nBulkVoltag = 14.0\n").find("t.toml:2: unknown parameter"), std::string::npos);
}

TEST(Scenario, ValueOutOfRange) {
  EXPECT_NE(errorOf("[battery]\nsoc_pct = 140\n").find("t.toml:2:"), std::string::npos);
  EXPECT_NE(errorOf("[config]\nBulkVoltage = 99\n").find("t.toml:2:"), std::string::npos);
  EXPECT_NE(errorOf("duration_s = 10\n[[events]]\nat_s = 20\nrpm = 1000\n").find("t.toml:3:"),
            std::string::npos);
  EXPECT_NE(errorOf("[[events]]\nat_s = 1\nset = { TempSource = 0.5 }\n").find("t.toml:3:"),
            std::string::npos);
}

TEST(Scenario, EventsOutOfOrder) {
  const auto e = errorOf("[[events]]\nat_s = 10\nrpm = 1\n[[events]]\nat_s = 5\nrpm = 2\n");
  EXPECT_NE(e.find("t.toml:4: events out of order"), std::string::npos) << e;
}

TEST(Scenario, FaultValueRules) {
  EXPECT_NE(errorOf("[[events]]\nat_s = 1\nfault = \"battery_v_offset\"\n").find("needs value"),
            std::string::npos);
  EXPECT_NE(errorOf("[[events]]\nat_s = 1\nfault = \"ina228_nack\"\nvalue = 3\n").find("value"),
            std::string::npos);
  EXPECT_NE(errorOf("[[events]]\nat_s = 1\ncommand = \"manual\"\n").find("needs duty"), std::string::npos);
  EXPECT_EQ(errorOf("[[events]]\nat_s = 1\ncommand = \"manual\"\nduty = 20\n"), "");
}

TEST(Scenario, PlantKeysParse) {
  const auto s = parseScenario(R"(
[battery]
chemistry = "lifepo4"
nominal_v = 24
temp_c = 5
ocv_soc_pct = [0, 50, 100]
ocv_cell_v = [2.9, 3.26, 3.40]
[alternator]
preset = "westerbeke-48"
rated_a = 60
field_tau_s = 0.12
[[events]]
at_s = 10
battery_temp_c = -5
)",
                               "t.toml");
  EXPECT_EQ(s.plant.battery.nominal_v, 24);
  EXPECT_EQ(s.plant.battery.temp_c, 5);
  ASSERT_EQ(s.plant.battery.ocv.size(), 3u);
  EXPECT_EQ(s.plant.battery.ocv[1].soc, 0.5);
  EXPECT_EQ(s.plant.alternator.preset, AlternatorPreset::westerbeke_48);
  EXPECT_EQ(s.plant.alternator.rated_a, 60);
  ASSERT_EQ(s.events.size(), 1u);
  EXPECT_EQ(*s.events[0].battery_temp_c, -5);
  const LundellParams m = resolveMachine(s.plant.alternator);
  EXPECT_NEAR(m.field_l_h / m.field_r_ohm, 0.12, 1e-12);
}

// Bad plant parameters: a file:line: error naming the key (the daemon
// exits 64 on it: tests/e2e/exit_paths.sh).
TEST(Scenario, BadPlantParametersHaveFileAndLine) {
  auto e = errorOf("name = \"x\"\n[alternator]\nfield_r_ohm = -2.5\n");
  EXPECT_EQ(e.rfind("t.toml:3:", 0), 0u) << e;
  EXPECT_NE(e.find("field_r_ohm"), std::string::npos) << e;
  e = errorOf("[alternator]\npulley_ratio = 3\ncut_in_rpm = 7000\n");  // 21 000 shaft rpm
  EXPECT_EQ(e.rfind("t.toml:3:", 0), 0u) << e;
  EXPECT_NE(e.find("maximum speed"), std::string::npos) << e;
  e = errorOf("[alternator]\nflux_k = 0.00001\n");  // a machine whose knee no speed reaches
  EXPECT_EQ(e.rfind("t.toml:1:", 0), 0u) << e;
  EXPECT_NE(e.find("knee"), std::string::npos) << e;
  e = errorOf("[battery]\nocv_soc_pct = [0, 50, 100]\nocv_cell_v = [3.0, 3.4, 3.3]\n");
  EXPECT_EQ(e.rfind("t.toml:3:", 0), 0u) << e;
  EXPECT_NE(e.find("monotone"), std::string::npos) << e;
  e = errorOf("[battery]\nocv_soc_pct = [0, 60, 50, 100]\nocv_cell_v = [3.0, 3.1, 3.2, 3.3]\n");
  EXPECT_EQ(e.rfind("t.toml:2:", 0), 0u) << e;
  e = errorOf("[battery]\nocv_soc_pct = [0, 100]\n");
  EXPECT_NE(e.find("go together"), std::string::npos) << e;
  e = errorOf("[alternator]\npreset = \"delco-10si\"\n");
  EXPECT_EQ(e.rfind("t.toml:2:", 0), 0u) << e;
  e = errorOf("[alternator]\nstator_rx_ohm = -0.1\n");
  EXPECT_EQ(e.rfind("t.toml:2:", 0), 0u) << e;
}

TEST(Scenario, MissingFileIsAClearError) {
  try {
    loadScenario("/nonexistent/x.toml");
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.toml"), std::string::npos);
  }
}

TEST(Scenario, ShippedExamplesLoad) {
  const std::filesystem::path dir = XR_SOURCE_DIR "/scenarios";
  int n = 0;
  for (const auto& f : std::filesystem::directory_iterator(dir)) {
    if (f.path().extension() != ".toml") continue;
    EXPECT_NO_THROW(loadScenario(f.path())) << f.path();
    Params p;
    EXPECT_NO_THROW(applyOverrides(p, loadScenario(f.path()).config)) << f.path();
    ++n;
  }
  EXPECT_GE(n, 3);
}

TEST(ScenarioPlayer, AppliesEventsInOrderAndHandsCommandsBack) {
  const Scenario s = parseScenario(
      "[[events]]\nat_s = 1\nrpm = 900\n[[events]]\nat_s = 2\nfault = \"field_open\"\n[[events]]\nat_s = 3\n"
      "command = \"off\"\n",
      "p.toml");
  HardwareSettings hw;
  WorldConfig wc;
  wc.plant = s.plant;
  SimWorld w(wc, hw);
  ScenarioPlayer pl(s);
  int controls = 0;
  auto on = [&](const ScenarioEvent& e) {
    ++controls;
    EXPECT_EQ(e.command->type, CommandType::Off);
  };
  pl.applyDue(0.5, w, on);
  EXPECT_EQ(w.plant().rpm(), 1800);
  pl.applyDue(1.0, w, on);
  EXPECT_EQ(w.plant().rpm(), 900);
  EXPECT_FALSE(w.faultActive(Fault::field_open));
  pl.applyDue(3.0, w, on);
  EXPECT_TRUE(w.faultActive(Fault::field_open));
  EXPECT_EQ(controls, 1);
  EXPECT_TRUE(pl.done());
}

}  // namespace
}  // namespace xr::sim
