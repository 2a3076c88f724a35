// The pairing button (app/pairing_button.h): a press held 50 ms opens the
// 2-minute pairing window once, with a security event; a contact's bounce or
// a glitch of a few ms does not; holding it counts once; without a
// [pairing] button_line nothing opens, and the simulator has no line either;
// a line another [hardware] key uses is refused at start.
#include "app/pairing_button.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/sim_wiring.h"
#include "config/config.h"
#include "drivers/sim/scenario.h"
#include "drivers/sim/sim_button.h"
#include "web/server/web_server.h"
#include "web_api_rig.h"

namespace xr::app {
namespace {

constexpr TimeNs ms(std::int64_t v) { return fromMs(v); }

int presses(ButtonPress& b, const std::vector<ButtonEdge>& edges, TimeNs pollAt) {
  int n = 0;
  for (const auto& e : edges) {
    n += b.at(e.at);
    n += b.feed(e);
  }
  return n + b.at(pollAt);
}

TEST(ButtonPress, AHoldOfFiftyMsCountsAndJustUnderDoesNot) {
  ButtonPress at;
  EXPECT_EQ(presses(at, {{true, ms(1000)}, {false, ms(1000 + kButtonHoldMs)}}, ms(2000)), 1);
  ButtonPress under;
  EXPECT_EQ(presses(under, {{true, ms(1000)}, {false, ms(1000 + kButtonHoldMs - 1)}}, ms(2000)), 0);
}

TEST(ButtonPress, AGlitchOfAFewMsOpensNothing) {
  ButtonPress b;
  EXPECT_EQ(presses(b, {{true, ms(500)}, {false, ms(503)}, {true, ms(900)}, {false, ms(910)}}, ms(5000)), 0);
}

TEST(ButtonPress, ABouncingContactThenAHoldCountsOnce) {
  ButtonPress b;
  // Bounces 1-2 ms apart for 8 ms, then held 200 ms, then a bouncing release.
  const std::vector<ButtonEdge> edges{{true, ms(100)}, {false, ms(101)}, {true, ms(103)}, {false, ms(104)},
                                      {true, ms(108)}, {false, ms(308)}, {true, ms(309)}, {false, ms(311)},
                                      {true, ms(312)}, {false, ms(313)}};
  EXPECT_EQ(presses(b, edges, ms(1000)), 1);
}

TEST(ButtonPress, HeldDownItCountsOnceWhilePolledAndNotAgainAtTheRelease) {
  ButtonPress b;
  EXPECT_FALSE(b.feed({true, ms(0)}));
  EXPECT_FALSE(b.at(ms(40)));
  EXPECT_TRUE(b.at(ms(100))) << "counts while still held: the window opens without waiting for the release";
  EXPECT_FALSE(b.at(ms(5000)));
  EXPECT_FALSE(b.feed({false, ms(8000)}));
  EXPECT_EQ(presses(b, {{true, ms(9000)}, {false, ms(9200)}}, ms(9300)), 1) << "the next press counts again";
}

struct Board {
  test::WebApiRig rig;
  web::WebServer server{*rig.api, [] {
                          web::WebServerOptions o;
                          o.port = 0;
                          o.token = "pairing-button-test-token";
                          return o;
                        }()};
  std::vector<std::string> events() const {
    std::vector<std::string> out;
    for (const auto& e : rig.recent.query(100, 0)) out.push_back(e.text);
    return out;
  }
};

TEST(PairingButtonWatch, APressOpensTheWindowWithOneEvent) {
  Board b;
  sim::SimButtonInput line;
  PairingButtonWatch w;
  w.poll(&line, ms(10'000), &b.server, b.rig.api.get());
  EXPECT_FALSE(b.server.pairingWindowOpen());
  line.setPressed(true, ms(10'050));
  line.setPressed(false, ms(10'250));
  w.poll(&line, ms(10'300), &b.server, b.rig.api.get());
  EXPECT_TRUE(b.server.pairingWindowOpen());
  ASSERT_EQ(b.events().size(), 1u);
  EXPECT_EQ(b.events()[0],
            "Pairing window opened for 2 min by the pairing button: one device may pair without a code");
  // Pressed again at once: the window again, not another event.
  line.setPressed(true, ms(11'000));
  w.poll(&line, ms(11'100), &b.server, b.rig.api.get());
  EXPECT_EQ(b.events().size(), 1u);
}

TEST(PairingButtonWatch, AGlitchOnTheLineOpensNothing) {
  Board b;
  sim::SimButtonInput line;
  PairingButtonWatch w;
  line.setPressed(true, ms(20'000));
  line.setPressed(false, ms(20'010));
  w.poll(&line, ms(20'100), &b.server, b.rig.api.get());
  w.poll(&line, ms(30'000), &b.server, b.rig.api.get());
  EXPECT_FALSE(b.server.pairingWindowOpen());
  EXPECT_TRUE(b.events().empty());
}

TEST(PairingButtonWatch, WithoutAButtonLineTheSimulatedPressOpensNothing) {
  const sim::Scenario sc = sim::parseScenario(R"(
duration_s = 10
[[events]]
at_s = 1
pairing_button = "pressed"
[[events]]
at_s = 2
pairing_button = "released"
)",
                                              "button.toml");
  ASSERT_EQ(sc.events.size(), 2u);
  EXPECT_EQ(sc.events[0].pairing_button, true);
  CliOptions cli;
  cli.sim = true;
  Settings settings;
  SimWiring none(sc, settings, cli, nullptr);
  EXPECT_EQ(none.pairingButton(), nullptr);
  Board b;
  PairingButtonWatch w;
  w.poll(none.pairingButton(), ms(3000), &b.server, b.rig.api.get());
  EXPECT_FALSE(b.server.pairingWindowOpen());
  settings.pairing.button_line = 17;
  SimWiring wired(sc, settings, cli, nullptr);
  EXPECT_NE(wired.pairingButton(), nullptr);
}

TEST(PairingButtonConfig, ALineOfItsOwnIsTakenAndALineInUseIsRefusedWithWhy) {
  const auto ok = loadConfigString("[pairing]\nbutton_line = 17\n", "ok.toml");
  ASSERT_TRUE(ok.ok()) << (ok.errors.empty() ? "" : ok.errors[0].toString());
  EXPECT_EQ(ok.config->settings.pairing.button_line, 17);
  const auto none = loadConfigString("", "none.toml");
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(none.config->settings.pairing.button_line, -1);
  const auto clash =
      loadConfigString("[hardware]\nfield_enable_line = 4\n[pairing]\nbutton_line = 4\n", "x.toml");
  ASSERT_EQ(clash.errors.size(), 1u);
  EXPECT_EQ(clash.errors[0].key, "pairing.button_line");
  EXPECT_NE(clash.errors[0].message.find("already [hardware] field_enable_line"), std::string::npos)
      << clash.errors[0].message;
  EXPECT_FALSE(loadConfigString("[pairing]\nbutton_line = 21\n", "buzzer.toml").errors.empty())
      << "21 is the buzzer's by default";
  EXPECT_FALSE(loadConfigString("[pairing]\nbutton_line = -2\n", "low.toml").errors.empty());
}

TEST(PairingButtonScenario, AnUnknownLevelIsRefusedWithItsLine) {
  try {
    sim::parseScenario("[[events]]\nat_s = 1\npairing_button = \"down\"\n", "bad.toml");
    FAIL() << "accepted";
  } catch (const sim::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("\"pressed\" or \"released\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace xr::app
