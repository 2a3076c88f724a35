// The set-up page's hardware choices through the daemon's side of the web
// API (app/web_api_hardware.cpp, docs/configuration.md "Set-up"): what the
// board has, a choice saved for the next start, and every refusal leaving
// the saved choice as it was.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/config_check.h"
#include "app/store_service.h"
#include "app/web_api.h"
#include "store_test_util.h"

namespace xr::app {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using xr::test::TempDir;

constexpr const char* kAlt = "28-00000000a001";
constexpr const char* kBat = "28-00000000b002";

// A board: two probes on the 1-Wire bus, a CAN interface and an Ethernet
// port, the file's settings, and a state database (or none).
struct HardwareRig {
  TempDir dir;
  Params params;
  rt::Handoffs handoffs{params};
  RecentEvents recent;
  std::unique_ptr<StoreService> store;
  Settings file;
  HardwareRig() {
    for (const char* id : {kAlt, kBat}) std::filesystem::create_directories(dir.path / "w1" / id);
    for (auto [name, type] : {std::pair{"can0", "280"}, std::pair{"eth0", "1"}}) {
      std::filesystem::create_directories(dir.path / "net" / name);
      std::ofstream(dir.path / "net" / name / "type") << type << "\n";
    }
  }
  std::unique_ptr<WebApi> api(const std::string& db = "x.db") {
    if (!db.empty()) store = std::make_unique<StoreService>(dir.file(db), 300);
    WebApiContext ctx;
    ctx.handoffs = &handoffs;
    ctx.store = store.get();
    ctx.events = &recent;
    ctx.fileSettings = file;
    ctx.runningSettings = store ? withHardwareChoices(file, store->loadHardwareChoices()) : file;
    ctx.w1Root = dir.file("w1");
    ctx.sysClassNet = dir.file("net");
    return std::make_unique<WebApi>(ctx);
  }
  void restart() {
    store->stop(BatteryLedger{}, false);
    store.reset();
  }
  ~HardwareRig() {
    if (store) store->stop(BatteryLedger{}, false);
  }
};

web::HardwareChoiceEdit battery(std::optional<std::string> v) { return {{true, std::move(v)}, {}, {}}; }
web::HardwareChoiceEdit bms(std::optional<std::string> v) { return {{}, {true, std::move(v)}, {}}; }
web::HardwareChoiceEdit pulley(std::optional<double> v) { return {{}, {}, {true, v}}; }

TEST(HardwareSetup, ListsTheProbesAndOnlyTheCanInterfaces) {
  HardwareRig r;
  const web::HardwareSetup h = r.api()->hardwareSetup();
  EXPECT_TRUE(h.savable);
  EXPECT_THAT(h.probes, ElementsAre(kAlt, kBat));
  EXPECT_EQ(h.alternatorSensor, kAlt) << "the first found, as the alternator's reader takes it";
  EXPECT_THAT(h.canInterfaces, ElementsAre("can0"));
  EXPECT_EQ(h.batteryTempSensor.running, "");
  EXPECT_FALSE(h.batteryTempSensor.chosen.has_value());
}

TEST(HardwareSetup, AChoiceIsSavedAnEventAndRunsFromTheNextStart) {
  HardwareRig r;
  auto api = r.api();
  EXPECT_TRUE(api->saveHardwareChoices(battery(kBat), "the phone").empty());
  const web::HardwareSetup now = api->hardwareSetup();
  EXPECT_EQ(now.batteryTempSensor.chosen, std::optional<std::string>(kBat));
  EXPECT_EQ(now.batteryTempSensor.running, "") << "the devices were opened at start";
  const auto events = r.store->queryEvents(10, std::nullopt);
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.front().code, "SetupHardware");
  EXPECT_EQ(events.front().message, std::string("Set-up by the phone: battery temperature probe ") + kBat +
                                        "; used from the next start of the regulator.");
  r.restart();
  EXPECT_EQ(r.api()->hardwareSetup().batteryTempSensor.running, kBat);
}

TEST(HardwareSetup, PrintConfigShowsWhatTheNextStartRuns) {
  HardwareRig r;
  ASSERT_TRUE(r.api()->saveHardwareChoices(battery(kBat), "the phone").empty());
  r.restart();
  std::ostringstream out, err;
  ASSERT_EQ(printConfigMain(std::nullopt, r.dir.file("x.db"), out, err), 0) << err.str();
  EXPECT_THAT(out.str(), HasSubstr(std::string("battery_temp_sensor = \"") + kBat + "\""));
  // One note per choice made, none for what the file still decides.
  EXPECT_EQ(err.str(), "note: battery_temp_sensor below is the set-up page's choice, not the file's\n");
}

// The tach reads the alternator; the RPM tables are in engine RPM. A pulley
// ratio is kept exactly and reaches the front end at the next start.
TEST(HardwareSetup, APulleyRatioIsKeptExactlyAndRunsFromTheNextStart) {
  HardwareRig r;
  auto api = r.api();
  ASSERT_TRUE(api->saveHardwareChoices(pulley(0.01), "the phone").empty()) << "the edge of the range";
  ASSERT_TRUE(api->saveHardwareChoices(pulley(2.7), "the phone").empty());
  EXPECT_EQ(r.store->queryEvents(1, std::nullopt).front().message,
            "Set-up by the phone: pulley ratio 2.7; used from the next start of the regulator.");
  EXPECT_DOUBLE_EQ(api->hardwareSetup().pulleyRatio.running, 1.0);
  r.restart();
  const web::HardwareSetup h = r.api()->hardwareSetup();
  EXPECT_EQ(h.pulleyRatio.chosen, std::optional<double>(2.7));
  EXPECT_EQ(h.pulleyRatio.running, 2.7);
}

TEST(HardwareSetup, NullGivesTheChoiceBackToTheFile) {
  HardwareRig r;
  r.file.can.bms_interface = "can0";
  auto api = r.api();
  ASSERT_TRUE(api->saveHardwareChoices(bms(""), "the phone").empty());
  EXPECT_EQ(r.store->loadHardwareChoices().bmsInterface, std::optional<std::string>(""));
  ASSERT_TRUE(api->saveHardwareChoices(bms(std::nullopt), "the phone").empty());
  EXPECT_FALSE(r.store->loadHardwareChoices().bmsInterface.has_value());
}

TEST(HardwareSetup, RefusalsSaveNothing) {
  HardwareRig r;
  r.file.can.n2k_interface = "can1";
  auto api = r.api();
  ASSERT_TRUE(api->saveHardwareChoices(battery(kBat), "the phone").empty());
  const HardwareChoices saved = r.store->loadHardwareChoices();
  struct Case {
    web::HardwareChoiceEdit edit;
    const char* key;
    const char* why;
  };
  const Case cases[] = {
      {battery("28-zz"), "hardware.battery_temp_sensor", "not a DS18B20 id"},
      {battery(kAlt), "hardware.battery_temp_sensor", "alternator's sensor"},
      // Filed under the setting the page sent (before: can.n2k_interface).
      {bms("can1"), "can.bms_interface", "is the NMEA 2000 bus"},
      {bms("can0/x"), "can.bms_interface", "not a CAN interface name"},
      {pulley(0.009), "hardware.frontend.pulley_ratio", "from 0.01 to 100"},
      {pulley(100.5), "hardware.frontend.pulley_ratio", "from 0.01 to 100"},
      {pulley(std::nan("")), "hardware.frontend.pulley_ratio", "from 0.01 to 100"},
  };
  for (const Case& c : cases) {
    const auto errors = api->saveHardwareChoices(c.edit, "the phone");
    ASSERT_EQ(errors.size(), 1u) << c.key;
    EXPECT_EQ(errors[0].name, c.key);
    EXPECT_THAT(errors[0].message, HasSubstr(c.why));
    EXPECT_EQ(r.store->loadHardwareChoices(), saved);
  }
}

TEST(HardwareSetup, TheAlternatorsNamedProbeIsRefusedOnce) {
  HardwareRig r;
  r.file.hardware.onewire_sensor_id = kBat;  // named: not the first found
  auto api = r.api();
  const auto errors = api->saveHardwareChoices(battery(kBat), "the phone");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_THAT(errors[0].message, HasSubstr("onewire_sensor_id"));
  EXPECT_TRUE(api->saveHardwareChoices(battery(kAlt), "the phone").empty()) << "the other probe is free";
}

TEST(HardwareSetup, ABmsOnCanIsRefusedWhileAVictronGxGivesTheLimits) {
  HardwareRig r;
  r.file.integrations.victron.enabled = true;
  r.file.integrations.victron.host = "venus.local";
  const auto errors = r.api()->saveHardwareChoices(bms("can0"), "the phone");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].name, "integrations.victron.enabled");
}

TEST(HardwareSetup, AChoiceThatCouldNotBeKeptIsRefused) {
  HardwareRig r;
  { std::ofstream(r.dir.file("afile")) << "x"; }
  auto api = r.api("afile/x.db");  // falls back to memory: nothing survives a restart
  const auto errors = api->saveHardwareChoices(battery(kBat), "the phone");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_THAT(errors[0].message, HasSubstr("would be lost at the next start"));
  HardwareRig bare;
  EXPECT_FALSE(bare.api("")->hardwareSetup().savable);
  EXPECT_THAT(bare.api("")->saveHardwareChoices(battery(kBat), "the phone")[0].message,
              HasSubstr("configuration file"));
}

}  // namespace
}  // namespace xr::app
