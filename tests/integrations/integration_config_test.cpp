// [integrations.*] in xregulator.toml (docs/integrations.md): the loader reads the nested
// tables, keeps them off by default, and refuses what an integration could
// not use with the key and line.
#include <gtest/gtest.h>

#include "config/config.h"

namespace xr {
namespace {

TEST(IntegrationConfig, OffByDefault) {
  auto r = loadConfigString("", "test.toml");
  ASSERT_TRUE(r.config) << (r.errors.empty() ? "" : r.errors[0].message);
  const auto& i = r.config->settings.integrations;
  EXPECT_FALSE(i.signalk.enabled);
  EXPECT_FALSE(i.mqtt.enabled);
  EXPECT_FALSE(i.victron.enabled);
  EXPECT_EQ(i.mqtt.discovery_prefix, "homeassistant");
}

TEST(IntegrationConfig, ReadsEachTable) {
  auto r = loadConfigString(R"([integrations.signalk]
enabled = true
url = "ws://boat:3000/signalk/v1/stream?subscribe=none"
[integrations.mqtt]
enabled = true
host = "ha.local"
port = 8883
username = "u"
password = "p"
tls = true
commands_enabled = true
[integrations.victron]
enabled = true
portal_id = "c0619ab1cafe"
battery_instance = 279
)",
                            "test.toml");
  ASSERT_TRUE(r.config) << (r.errors.empty() ? "" : r.errors[0].key + ": " + r.errors[0].message);
  const auto& i = r.config->settings.integrations;
  EXPECT_TRUE(i.signalk.enabled);
  EXPECT_EQ(i.signalk.url, "ws://boat:3000/signalk/v1/stream?subscribe=none");
  EXPECT_EQ(i.mqtt.port, 8883);
  EXPECT_TRUE(i.mqtt.tls);
  EXPECT_TRUE(i.mqtt.commands_enabled);
  EXPECT_EQ(i.victron.battery_instance, 279);
}

TEST(IntegrationConfig, DottedKeysInTheParentTableWorkToo) {
  auto r = loadConfigString("[integrations]\nmqtt.enabled = true\n", "test.toml");
  ASSERT_TRUE(r.config);
  EXPECT_TRUE(r.config->settings.integrations.mqtt.enabled);
}

TEST(IntegrationConfig, ErrorsNameTheKeyAndLine) {
  auto r = loadConfigString("[integrations.mqtt]\nenabled = true\ncommands_enabled = true\n", "test.toml");
  ASSERT_FALSE(r.config);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].key, "integrations.mqtt.commands_enabled");
  EXPECT_EQ(r.errors[0].line, 3);
  auto u = loadConfigString("[integrations.mqtt]\nprot = 1883\n", "test.toml");
  ASSERT_FALSE(u.config);
  EXPECT_NE(u.errors[0].message.find("did you mean port"), std::string::npos) << u.errors[0].message;
  auto p = loadConfigString("[integrations.victron]\nport = 70000\n", "test.toml");
  ASSERT_FALSE(p.config);
  EXPECT_EQ(p.errors[0].key, "integrations.victron.port");
}

// One source of BMS limits: a GX and a BMS on CAN together are refused
// (exit 78), at the Victron key's line.
TEST(IntegrationConfig, VictronAndACanBmsTogetherAreRefused) {
  const char* both = R"([can]
bms_interface = "can0"
[integrations.victron]
portal_id = "c0619ab1cafe"
enabled = true
)";
  auto r = loadConfigString(both, "test.toml");
  ASSERT_FALSE(r.config);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].key, "integrations.victron.enabled");
  EXPECT_EQ(r.errors[0].line, 5);
  EXPECT_NE(r.errors[0].message.find("can0"), std::string::npos) << r.errors[0].message;
  // Either alone is fine.
  EXPECT_TRUE(loadConfigString("[can]\nbms_interface = \"can0\"\n", "test.toml").config);
  EXPECT_TRUE(loadConfigString("[can]\nbms_interface = \"can0\"\n[integrations.victron]\nenabled = false\n",
                               "test.toml")
                  .config);
}

// stale_s gave way to the BmsStaleS parameter: the loader says where it went.
TEST(IntegrationConfig, RetiredStaleSNamesItsReplacement) {
  auto r = loadConfigString("[integrations.victron]\nstale_s = 10.0\n", "test.toml");
  ASSERT_FALSE(r.config);
  EXPECT_EQ(r.errors[0].key, "integrations.victron.stale_s");
  EXPECT_NE(r.errors[0].message.find("BmsStaleS"), std::string::npos) << r.errors[0].message;
}

}  // namespace
}  // namespace xr
