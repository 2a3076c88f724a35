// Home Assistant discovery documents and the state document (docs/integrations.md),
// without a broker: topics, the fields Home Assistant requires, units.
#include "integrations/ha_discovery.h"

#include <gtest/gtest.h>

#include <boost/json.hpp>
#include <set>

namespace xr::integrations {
namespace {

namespace json = boost::json;

HaTopics topics() { return HaTopics{"homeassistant", "boat1"}; }

json::object find(const std::vector<MqttMessage>& all, const std::string& topic) {
  for (const auto& m : all)
    if (m.topic == topic) return json::parse(m.payload).as_object();
  ADD_FAILURE() << "no config on " << topic;
  return {};
}

TEST(HaDiscovery, SensorsAndBinarySensorsWithoutCommands) {
  const auto all = discoveryConfigs(topics(), false, "1.2.3");
  std::set<std::string> names;
  for (const auto& m : all) names.insert(m.topic);
  EXPECT_EQ(all.size(), 22u);
  EXPECT_EQ(names.size(), 22u);
  // The incident acting now and its start/end events (docs/integrations.md "Alarms that reach the owner").
  EXPECT_TRUE(names.count("homeassistant/binary_sensor/xregulator_boat1/incident/config"));
  EXPECT_TRUE(names.count("homeassistant/event/xregulator_boat1/incident/config"));
  EXPECT_TRUE(names.count("homeassistant/sensor/xregulator_boat1/capacity_measured/config"));
  EXPECT_TRUE(names.count("homeassistant/sensor/xregulator_boat1/alternator_life_used/config"));
  EXPECT_TRUE(names.count("homeassistant/sensor/xregulator_boat1/battery_voltage/config"));
  EXPECT_TRUE(names.count("homeassistant/binary_sensor/xregulator_boat1/alarm/config"));
  EXPECT_FALSE(names.count("homeassistant/select/xregulator_boat1/regulator_mode/config"));
  EXPECT_FALSE(names.count("homeassistant/button/xregulator_boat1/limp_home/config"));
}

TEST(HaDiscovery, CommandsAddSelectAndButton) {
  const auto all = discoveryConfigs(topics(), true, "1.2.3");
  EXPECT_EQ(all.size(), 24u);
  auto sel = find(all, "homeassistant/select/xregulator_boat1/regulator_mode/config");
  EXPECT_EQ(sel.at("command_topic").as_string(), "xregulator/boat1/set/mode");
  EXPECT_EQ(json::serialize(sel.at("options")), R"(["off","auto"])");
  auto btn = find(all, "homeassistant/button/xregulator_boat1/limp_home/config");
  EXPECT_EQ(btn.at("command_topic").as_string(), "xregulator/boat1/set/limp_home");
  EXPECT_EQ(btn.at("payload_press").as_string(), "PRESS");
}

TEST(HaDiscovery, EveryConfigHasTheRequiredFieldsAndOneDevice) {
  for (const auto& m : discoveryConfigs(topics(), true, "1.2.3")) {
    SCOPED_TRACE(m.topic);
    auto o = json::parse(m.payload).as_object();
    EXPECT_TRUE(o.contains("name"));
    EXPECT_TRUE(o.at("unique_id").as_string().starts_with("xregulator_boat1_"));
    EXPECT_EQ(o.at("availability_topic").as_string(), "xregulator/boat1/availability");
    const auto& dev = o.at("device").as_object();
    EXPECT_EQ(json::serialize(dev.at("identifiers")), R"(["xregulator_boat1"])");
    EXPECT_EQ(dev.at("sw_version").as_string(), "1.2.3");
  }
}

TEST(HaDiscovery, UnitsAndDeviceClasses) {
  const auto all = discoveryConfigs(topics(), false, "x");
  auto temp = find(all, "homeassistant/sensor/xregulator_boat1/alternator_temperature/config");
  EXPECT_EQ(temp.at("unit_of_measurement").as_string(), "°C");
  EXPECT_EQ(temp.at("device_class").as_string(), "temperature");
  auto energy = find(all, "homeassistant/sensor/xregulator_boat1/charged_energy/config");
  EXPECT_EQ(energy.at("unit_of_measurement").as_string(), "kWh");
  EXPECT_EQ(energy.at("state_class").as_string(), "total_increasing");
  auto stage = find(all, "homeassistant/sensor/xregulator_boat1/stage/config");
  EXPECT_FALSE(stage.contains("unit_of_measurement"));
  auto field = find(all, "homeassistant/binary_sensor/xregulator_boat1/field/config");
  EXPECT_EQ(field.at("payload_on").as_string(), "ON");
}

TEST(HaDiscovery, StateDocumentCarriesEveryEntityInItsUnit) {
  IntegrationSample s;
  s.valid = true;
  s.battery_v = 13.8123;
  s.alt_a = 55.5;
  s.alt_temp_c = 71.26;
  s.field_pct = 42.0;
  s.field_on = true;
  s.power_w = 13.8123 * 55.5;
  s.charged_kwh = 1.2345;
  s.stage = "ABSORPTION";
  s.mode = "MODE_NORMAL_AUTO_PID";
  auto o = json::parse(stateJson(s)).as_object();
  EXPECT_DOUBLE_EQ(o.at("battery_voltage").as_double(), 13.812);
  EXPECT_DOUBLE_EQ(o.at("alternator_temperature").as_double(), 71.3);
  EXPECT_DOUBLE_EQ(o.at("power").as_double(), 767.0);
  EXPECT_DOUBLE_EQ(o.at("charged_energy").as_double(), 1.235);
  EXPECT_EQ(o.at("field").as_string(), "ON");
  EXPECT_EQ(o.at("alarm").as_string(), "OFF");
  EXPECT_EQ(o.at("stage").as_string(), "ABSORPTION");
  EXPECT_EQ(o.at("regulator_mode").as_string(), "auto");
  s.operatorOff = true;
  EXPECT_EQ(json::parse(stateJson(s)).as_object().at("regulator_mode").as_string(), "off");
}

// The owner model's words (docs/integrations.md "The owner model in Home
// Assistant and Signal K"): the same function as the dashboard's.
TEST(HaDiscovery, ChargingStateAndLimitedByComeFromTheOwnerModel) {
  Telemetry t;
  t.mode = FieldControlMode::MODE_NORMAL_AUTO_PID;
  t.control.sysMode = SysMode::SYS_MODE_AUTO;
  t.field_enable = true;
  t.alt_a = 30.0;
  t.bcur_a = 27.0;
  t.caps.ratingA = 120.0;
  t.caps.batteryTempA = 28.0;
  t.caps.batteryTempCause = BatteryTempCap::NO_PROBE;
  rt::RuntimeSnapshot snap;
  snap.tick = 1;
  snap.telemetry = t;
  auto o = json::parse(stateJson(sampleOf(snap))).as_object();
  EXPECT_EQ(o.at("charging_state").as_string(), "Charging · Bulk · limited by C/10 without a battery probe");
  EXPECT_EQ(o.at("limited_by").as_string(), "C/10 without a battery probe: 28 A");
  EXPECT_DOUBLE_EQ(o.at("limit_amps").as_double(), 28.0);
  EXPECT_EQ(o.at("limits").as_array().at(0).at("id").as_string(), "battery_temp_required");
  auto cfg = find(discoveryConfigs(topics(), false, "1"), "homeassistant/sensor/xregulator_boat1/limited_by/config");
  EXPECT_EQ(cfg.at("json_attributes_topic").as_string(), "xregulator/boat1/state");
}

TEST(HaDiscovery, NonFiniteValuesBecomeNull) {
  IntegrationSample s;
  s.battery_v = std::numeric_limits<double>::quiet_NaN();
  auto o = json::parse(stateJson(s)).as_object();
  EXPECT_TRUE(o.at("battery_voltage").is_null());
  // Not measured yet: null, never a made-up 0.
  EXPECT_TRUE(o.at("capacity_measured").is_null());
  EXPECT_TRUE(o.at("battery_resistance").is_null());
}

TEST(HaDiscovery, TheHealthFiguresAreInTheState) {
  IntegrationSample s;
  s.capacity_measured_ah = 154.23;
  s.battery_r_mohm = 3.504;
  s.alt_run_hours = 12.3456;
  s.alt_life_used_pct = 0.012345;
  s.belt_slip_events = 1;
  auto o = json::parse(stateJson(s)).as_object();
  EXPECT_DOUBLE_EQ(o.at("capacity_measured").as_double(), 154.0);
  EXPECT_DOUBLE_EQ(o.at("battery_resistance").as_double(), 3.5);
  EXPECT_DOUBLE_EQ(o.at("alternator_run_hours").as_double(), 12.35);
  EXPECT_DOUBLE_EQ(o.at("alternator_life_used").as_double(), 0.0123);
  EXPECT_DOUBLE_EQ(o.at("belt_slips").as_double(), 1.0);
}

TEST(SignalKWords, ChargingModeFollowsTheStage) {
  EXPECT_EQ(signalKChargingMode(ChargeStage::BULK, true), "bulk");
  EXPECT_EQ(signalKChargingMode(ChargeStage::ABSORPTION, true), "acceptance");
  EXPECT_EQ(signalKChargingMode(ChargeStage::FLOAT, true), "float");
  EXPECT_EQ(signalKChargingMode(ChargeStage::IDLE, true), "other");
  EXPECT_EQ(signalKChargingMode(ChargeStage::BULK, false), "other");
}

// A command is an exact word on its own topic; anything else is refused with
// a reason (counted, never applied), and other topics are not commands.
TEST(HaDiscovery, CommandsAreExactWordsOnTheirTopics) {
  const HaTopics t{"homeassistant", "boat1"};
  EXPECT_EQ(decodeHaCommand(t, t.modeCommand(), "off").command, CommandType::Off);
  EXPECT_EQ(decodeHaCommand(t, t.modeCommand(), "auto").command, CommandType::Auto);
  EXPECT_EQ(decodeHaCommand(t, t.limpHomeCommand(), "PRESS").command, CommandType::LimpHome);
  for (const char* bad : {"OFF", "off ", "", "limp", "PRESS"}) {
    const auto d = decodeHaCommand(t, t.modeCommand(), bad);
    EXPECT_FALSE(d.command) << bad;
    EXPECT_FALSE(d.refused.empty()) << bad;
  }
  EXPECT_FALSE(decodeHaCommand(t, t.limpHomeCommand(), "press").command);
  const auto other = decodeHaCommand(t, "xregulator/boat2/set/mode", "off");
  EXPECT_FALSE(other.command);
  EXPECT_TRUE(other.refused.empty());
}

}  // namespace
}  // namespace xr::integrations
