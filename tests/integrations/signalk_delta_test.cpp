// Signal K deltas and meta (docs/integrations.md) without a server: paths, SI units,
// the chargingMode words, values left out when unknown; the URL parser and
// the [integrations.*] checks of the loader.
#include "integrations/signalk_delta.h"

#include <gtest/gtest.h>

#include <boost/json.hpp>
#include <map>

#include "config/integration_checks.h"
#include "integrations/signalk_client.h"

namespace xr::integrations {
namespace {

namespace json = boost::json;

IntegrationSample sample() {
  IntegrationSample s;
  s.valid = true;
  s.battery_v = 14.2;
  s.battery_a = 30.0;
  s.alt_a = 60.0;
  s.alt_temp_c = 80.0;
  s.rpm = 3000.0;
  s.field_pct = 45.0;
  s.field_on = true;
  s.setpoint_v = 14.4;
  s.setpoint_a = 90.0;
  s.soc_pct = 72.0;
  s.time_to_empty_s = -1;
  s.stageValue = ChargeStage::ABSORPTION;
  return s;
}

std::map<std::string, json::value> valuesOf(const std::string& delta) {
  std::map<std::string, json::value> m;
  auto d = json::parse(delta).as_object();
  EXPECT_EQ(d.at("context").as_string(), "vessels.self");
  for (const auto& v : d.at("updates").as_array()[0].as_object().at("values").as_array())
    m[std::string(v.as_object().at("path").as_string())] = v.as_object().at("value");
  return m;
}

TEST(SignalKDelta, PathsInSiUnits) {
  auto m = valuesOf(signalKDelta(signalKValues(sample(), "main", "house"), "2026-12-03T14:00:00.000Z"));
  EXPECT_DOUBLE_EQ(m.at("electrical.alternators.main.voltage").as_double(), 14.2);
  EXPECT_DOUBLE_EQ(m.at("electrical.alternators.main.current").as_double(), 60.0);
  EXPECT_DOUBLE_EQ(m.at("electrical.alternators.main.temperature").as_double(), 353.15);  // K
  EXPECT_DOUBLE_EQ(m.at("electrical.alternators.main.revolutions").as_double(), 50.0);    // Hz
  EXPECT_DOUBLE_EQ(m.at("electrical.alternators.main.fieldDrive").as_double(), 0.45);     // ratio
  EXPECT_EQ(m.at("electrical.alternators.main.chargingMode").as_string(), "acceptance");
  EXPECT_DOUBLE_EQ(m.at("electrical.alternators.main.setpointVoltage").as_double(), 14.4);
  EXPECT_DOUBLE_EQ(m.at("electrical.alternators.main.setpointCurrent").as_double(), 90.0);
  EXPECT_DOUBLE_EQ(m.at("electrical.alternators.main.weatherMode").as_double(), 0.0);
  EXPECT_DOUBLE_EQ(m.at("electrical.batteries.house.voltage").as_double(), 14.2);
  EXPECT_DOUBLE_EQ(m.at("electrical.batteries.house.current").as_double(), 30.0);
  EXPECT_DOUBLE_EQ(m.at("electrical.batteries.house.capacity.stateOfCharge").as_double(), 0.72);
  // Unknown: no battery temperature sensor, no time remaining while charging.
  EXPECT_EQ(m.count("electrical.batteries.house.temperature"), 0u);
  EXPECT_EQ(m.count("electrical.batteries.house.capacity.timeRemaining"), 0u);
}

TEST(SignalKDelta, KnownValuesAreSentAndNaNIsLeftOut) {
  auto s = sample();
  s.time_to_empty_s = 7200;
  s.battery_temp_c = 25.0;
  s.alt_a = std::numeric_limits<double>::quiet_NaN();
  auto m = valuesOf(signalKDelta(signalKValues(s, "a1", "b1"), "t"));
  EXPECT_DOUBLE_EQ(m.at("electrical.batteries.b1.capacity.timeRemaining").as_double(), 7200.0);
  EXPECT_DOUBLE_EQ(m.at("electrical.batteries.b1.temperature").as_double(), 298.15);
  EXPECT_EQ(m.count("electrical.alternators.a1.current"), 0u);
  // Not measured yet: no capacity, no resistance.
  EXPECT_EQ(m.count("electrical.batteries.b1.capacity.actual"), 0u);
  EXPECT_EQ(m.count("electrical.batteries.b1.internalResistance"), 0u);
  s.capacity_measured_ah = 154.0;
  s.nominal_v = 12.0;
  s.battery_r_mohm = 3.5;
  m = valuesOf(signalKDelta(signalKValues(s, "a1", "b1"), "t"));
  EXPECT_DOUBLE_EQ(m.at("electrical.batteries.b1.capacity.actual").as_double(), 154.0 * 12.0 * 3600.0);
  EXPECT_DOUBLE_EQ(m.at("electrical.batteries.b1.internalResistance").as_double(), 0.0035);
}

TEST(SignalKDelta, TheOwnerModelsStateAndFirstLimitAreSent) {
  auto s = sample();
  s.ownerState = "Charging · Bulk · limited by Belt limit";
  s.limitedBy = "Belt limit: 100 A";
  s.limitAmps = 100.0;
  auto m = valuesOf(signalKDelta(signalKValues(s, "a1", "b1"), "t"));
  EXPECT_EQ(m.at("electrical.alternators.a1.chargingState").as_string(), "Charging · Bulk · limited by Belt limit");
  EXPECT_EQ(m.at("electrical.alternators.a1.limitedBy").as_string(), "Belt limit: 100 A");
  EXPECT_DOUBLE_EQ(m.at("electrical.alternators.a1.currentLimit").as_double(), 100.0);
}

TEST(SignalKDelta, MetaHasUnitsAndNamesForEveryPath) {
  auto d = json::parse(signalKMetaDelta(signalKMeta("main", "house"))).as_object();
  std::map<std::string, json::object> meta;
  for (const auto& m : d.at("updates").as_array()[0].as_object().at("meta").as_array())
    meta[std::string(m.as_object().at("path").as_string())] = m.as_object().at("value").as_object();
  EXPECT_EQ(meta.size(), 22u);
  EXPECT_EQ(meta.at("electrical.alternators.main.currentLimit").at("units").as_string(), "A");
  EXPECT_EQ(meta.at("electrical.batteries.house.capacity.actual").at("units").as_string(), "J");
  EXPECT_EQ(meta.at("electrical.alternators.main.insulationLifeUsed").at("units").as_string(), "ratio");
  EXPECT_EQ(meta.at("electrical.alternators.main.temperature").at("units").as_string(), "K");
  EXPECT_EQ(meta.at("electrical.alternators.main.revolutions").at("units").as_string(), "Hz");
  EXPECT_EQ(meta.at("electrical.alternators.main.fieldDrive").at("units").as_string(), "ratio");
  EXPECT_EQ(meta.at("electrical.batteries.house.capacity.timeRemaining").at("units").as_string(), "s");
  EXPECT_FALSE(meta.at("electrical.alternators.main.chargingMode").contains("units"));
  for (const auto& [path, v] : meta) EXPECT_TRUE(v.contains("displayName")) << path;
}

TEST(SignalKDelta, IsoTime) {
  EXPECT_EQ(isoTimeUtc(0), "1970-01-01T00:00:00.000Z");
  EXPECT_EQ(isoTimeUtc(1700000000123LL), "2023-11-14T22:13:20.123Z");
}

TEST(SignalKUrl, Parses) {
  auto u = parseWsUrl("ws://boat.local:3000/signalk/v1/stream?subscribe=none");
  ASSERT_TRUE(u);
  EXPECT_EQ(u->host, "boat.local");
  EXPECT_EQ(u->port, "3000");
  EXPECT_EQ(u->target, "/signalk/v1/stream?subscribe=none");
  EXPECT_EQ(parseWsUrl("ws://h")->port, "80");
  EXPECT_FALSE(parseWsUrl("http://h:3000/"));
  EXPECT_FALSE(parseWsUrl("ws://h:abc/"));
}

TEST(IntegrationChecks, DefaultsAreUsable) { EXPECT_TRUE(checkIntegrations(IntegrationsSettings{}).empty()); }

TEST(IntegrationChecks, RefusesWhatAnIntegrationCouldNotUse) {
  IntegrationsSettings s;
  s.signalk.url = "wss://x/";
  s.signalk.alternator_id = "main-1";
  s.mqtt.commands_enabled = true;  // no credentials
  s.mqtt.discovery_prefix = "home/#";
  s.victron.enabled = true;
  s.victron.portal_id = "";
  std::map<std::string, std::string> errors;
  for (auto& [k, m] : checkIntegrations(s)) errors[k] = m;
  EXPECT_TRUE(errors.count("integrations.signalk.url"));
  EXPECT_TRUE(errors.count("integrations.signalk.alternator_id"));
  EXPECT_TRUE(errors.count("integrations.mqtt.commands_enabled"));
  EXPECT_TRUE(errors.count("integrations.mqtt.discovery_prefix"));
  EXPECT_TRUE(errors.count("integrations.victron.portal_id"));
  EXPECT_EQ(errors.size(), 5u);
}

TEST(IntegrationChecks, CommandsWithCredentialsAreAllowed) {
  IntegrationsSettings s;
  s.mqtt.commands_enabled = true;
  s.mqtt.username = "ha";
  s.mqtt.password = "secret";
  EXPECT_TRUE(checkIntegrations(s).empty());
}

}  // namespace
TEST(SignalKDelta, WeatherModeIsOneWhileItRestsTheAlternator) {
  auto s = sample();
  s.reason = "REASON_WEATHER_MODE";
  auto m = valuesOf(signalKDelta(signalKValues(s, "main", "house"), "2026-12-03T14:00:00.000Z"));
  EXPECT_DOUBLE_EQ(m.at("electrical.alternators.main.weatherMode").as_double(), 1.0);
}

}  // namespace xr::integrations
