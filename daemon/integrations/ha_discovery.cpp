#include "integrations/ha_discovery.h"

#include <boost/json.hpp>
#include <cmath>
#include <string_view>

namespace xr::integrations {

namespace json = boost::json;

namespace {

struct SensorDef {
  const char* object;       // object id and state key
  const char* name;         // shown in Home Assistant (prefixed by the device name)
  const char* unit;         // "" = none
  const char* deviceClass;  // "" = none
  const char* stateClass;   // "" = none
  const char* icon;         // "" = the device class's
};

// What an owner watches (docs/integrations.md): battery V, battery A, alternator A, alternator degC, SoC,
// field %, power W, stage, mode, charged kWh; the measured capacity and resistance, the
// alternator's hours, insulation life used and belt slips.
constexpr SensorDef kSensors[] = {
    {"battery_voltage", "Battery voltage", "V", "voltage", "measurement", ""},
    {"battery_current", "Battery current", "A", "current", "measurement", ""},
    {"alternator_current", "Alternator current", "A", "current", "measurement", ""},
    {"alternator_temperature", "Alternator temperature", "°C", "temperature", "measurement", ""},
    {"soc", "State of charge", "%", "battery", "measurement", ""},
    {"field_duty", "Field duty", "%", "", "measurement", "mdi:sine-wave"},
    {"power", "Alternator power", "W", "power", "measurement", ""},
    {"stage", "Charging stage", "", "", "", "mdi:battery-charging"},
    {"mode", "Regulator mode", "", "", "", "mdi:state-machine"},
    {"charged_energy", "Charged energy", "kWh", "energy", "total_increasing", ""},
    // What the regulator learns (docs/batteries.md, docs/operations.md "Alternator wear").
    {"capacity_measured", "Battery capacity measured", "Ah", "", "measurement", "mdi:battery-heart-variant"},
    {"battery_resistance", "Battery resistance (25 °C)", "mΩ", "", "measurement", "mdi:omega"},
    {"alternator_run_hours", "Alternator running hours", "h", "duration", "total_increasing", ""},
    {"alternator_life_used", "Alternator insulation life used", "%", "", "total_increasing",
     "mdi:timer-sand"},
    {"belt_slips", "Alternator belt slips", "", "", "total_increasing", "mdi:car-tire-alert"},
    // The owner model's words (docs/dashboard.md "Owner model"), as the dashboard shows them.
    {"charging_state", "Charging state", "", "", "", "mdi:information-outline"},
    {"limited_by", "Limited by", "", "", "", "mdi:speedometer-slow"},
};

struct BinaryDef {
  const char* object;
  const char* name;
  const char* deviceClass;
};
constexpr BinaryDef kBinary[] = {
    {"field", "Field enabled", "power"},
    {"alarm", "Alarm", "problem"},
    // The regulator resting the alternator for the sun (docs/integrations.md "Weather").
    {"weather_mode", "Weather mode", ""},
};

json::object deviceBlock(const HaTopics& t, const std::string& version) {
  json::object d;
  d["identifiers"] = json::array{"xregulator_" + t.id};
  d["name"] = "xregulator " + t.id;
  d["manufacturer"] = "xregulator";
  d["model"] = "alternator field regulator";
  d["sw_version"] = version;
  return d;
}

json::object common(const HaTopics& t, const std::string& object, const char* name,
                    const std::string& version) {
  json::object o;
  o["name"] = name;
  o["unique_id"] = "xregulator_" + t.id + "_" + object;
  o["object_id"] = "xregulator_" + t.id + "_" + object;
  o["availability_topic"] = t.availability();
  o["payload_available"] = "online";
  o["payload_not_available"] = "offline";
  o["device"] = deviceBlock(t, version);
  return o;
}

json::value number(double v, int decimals) {
  if (!std::isfinite(v)) return nullptr;
  const double scale = std::pow(10.0, decimals);
  return std::round(v * scale) / scale;
}

}  // namespace

std::vector<MqttMessage> discoveryConfigs(const HaTopics& t, bool withCommands, const std::string& version) {
  std::vector<MqttMessage> out;
  for (const auto& s : kSensors) {
    json::object o = common(t, s.object, s.name, version);
    o["state_topic"] = t.state();
    o["value_template"] = std::string("{{ value_json.") + s.object + " }}";
    if (*s.unit) o["unit_of_measurement"] = s.unit;
    if (*s.deviceClass) o["device_class"] = s.deviceClass;
    if (*s.stateClass) o["state_class"] = s.stateClass;
    if (*s.icon) o["icon"] = s.icon;
    // Every limit acting now, with its amps and cause, as the sensor's attributes.
    if (std::string_view(s.object) == "limited_by") {
      o["json_attributes_topic"] = t.state();
      o["json_attributes_template"] =
          "{{ {'limits': value_json.limits, 'limit_amps': value_json.limit_amps} | tojson }}";
    }
    out.push_back({t.config("sensor", s.object), json::serialize(o)});
  }
  for (const auto& b : kBinary) {
    json::object o = common(t, b.object, b.name, version);
    o["state_topic"] = t.state();
    o["value_template"] = std::string("{{ value_json.") + b.object + " }}";
    o["payload_on"] = "ON";
    o["payload_off"] = "OFF";
    if (*b.deviceClass) o["device_class"] = b.deviceClass;
    out.push_back({t.config("binary_sensor", b.object), json::serialize(o)});
  }
  // Alarms that reach the owner (docs/integrations.md): the incident acting
  // now, with its title and what to do as attributes, and an event entity
  // that fires at each start and end, for the owner's own automations.
  json::object inc = common(t, "incident", "Incident", version);
  inc["state_topic"] = t.state();
  inc["value_template"] = "{{ value_json.incident }}";
  inc["payload_on"] = "ON";
  inc["payload_off"] = "OFF";
  inc["device_class"] = "problem";
  inc["json_attributes_topic"] = t.state();
  inc["json_attributes_template"] = "{{ value_json.incident_detail | tojson }}";
  out.push_back({t.config("binary_sensor", "incident"), json::serialize(inc)});
  json::object ev = common(t, "incident", "Incident", version);
  ev["state_topic"] = t.incidentEvent();
  ev["event_types"] = json::array{"start", "end"};
  ev["icon"] = "mdi:alert";
  out.push_back({t.config("event", "incident"), json::serialize(ev)});
  if (withCommands) {
    json::object sel = common(t, "regulator_mode", "Regulator on/off", version);
    sel["command_topic"] = t.modeCommand();
    sel["state_topic"] = t.state();
    sel["value_template"] = "{{ value_json.regulator_mode }}";
    sel["options"] = json::array{"off", "auto"};
    sel["retain"] = false;  // a command is an action, never a state (docs/security.md)
    sel["icon"] = "mdi:power";
    out.push_back({t.config("select", "regulator_mode"), json::serialize(sel)});
    json::object btn = common(t, "limp_home", "Limp home", version);
    btn["command_topic"] = t.limpHomeCommand();
    btn["payload_press"] = "PRESS";
    btn["retain"] = false;
    btn["icon"] = "mdi:car-emergency";
    out.push_back({t.config("button", "limp_home"), json::serialize(btn)});
  }
  return out;
}

std::string regulatorModeOption(const IntegrationSample& s) { return s.operatorOff ? "off" : "auto"; }

namespace {
json::object incidentDetail(const IncidentWords& w) {
  return json::object{
      {"title", w.title},         {"what_happened", w.whatHappened},
      {"what_to_do", w.whatToDo}, {"severity", w.severity},
      {"start", w.startIso},      {"end", w.endIso.empty() ? json::value(nullptr) : json::value(w.endIso)}};
}
}  // namespace

std::string incidentEventJson(const IncidentEdge& e, const IncidentWords& words) {
  json::object o = incidentDetail(words);
  o["event_type"] = e.start ? "start" : "end";
  o["incident_id"] = e.incident.id;
  return json::serialize(o);
}

std::string stateJson(const IntegrationSample& s, const IncidentWords* incident) {
  json::object o;
  o["incident"] = incident ? "ON" : "OFF";
  o["incident_detail"] = incident ? json::value(incidentDetail(*incident)) : json::value(json::object{});
  o["battery_voltage"] = number(s.battery_v, 3);
  o["battery_current"] = number(s.battery_a, 2);
  o["alternator_current"] = number(s.alt_a, 2);
  o["alternator_temperature"] = number(s.alt_temp_c, 1);
  o["soc"] = number(s.soc_pct, 1);
  o["field_duty"] = number(s.field_pct, 1);
  o["power"] = number(s.power_w, 0);
  o["stage"] = s.stage;
  o["mode"] = s.mode;
  o["reason"] = s.reason;
  o["charged_energy"] = number(s.charged_kwh, 3);
  o["capacity_measured"] = number(s.capacity_measured_ah, 0);
  o["battery_resistance"] = number(s.battery_r_mohm, 2);
  o["alternator_run_hours"] = number(s.alt_run_hours, 2);
  o["alternator_life_used"] = number(s.alt_life_used_pct, 4);
  o["belt_slips"] = number(s.belt_slip_events, 0);
  o["field"] = s.field_on ? "ON" : "OFF";
  o["alarm"] = s.alarm ? "ON" : "OFF";
  o["weather_mode"] = s.reason == "REASON_WEATHER_MODE" ? "ON" : "OFF";
  o["charging_state"] = s.ownerState;
  o["limited_by"] = s.limitedBy;
  o["limit_amps"] = number(s.limitAmps, 1);
  o["soc_source"] = s.socSource;
  json::array limits;
  for (const auto& l : s.limits)
    limits.push_back(
        json::object{{"id", l.id}, {"what", l.what}, {"amps", number(l.amps, 1)}, {"why", l.why}});
  o["limits"] = std::move(limits);
  o["regulator_mode"] = regulatorModeOption(s);
  return json::serialize(o);
}

HaCommandDecision decodeHaCommand(const HaTopics& t, std::string_view topic, std::string_view payload) {
  HaCommandDecision d;
  if (topic == t.modeCommand()) {
    if (payload == "off")
      d.command = CommandType::Off;
    else if (payload == "auto")
      d.command = CommandType::Auto;
    else
      d.refused = "mode command '" + std::string(payload.substr(0, 32)) + "' is not off or auto";
  } else if (topic == t.limpHomeCommand()) {
    if (payload == "PRESS")
      d.command = CommandType::LimpHome;
    else
      d.refused = "limp home command payload is not PRESS";
  }
  return d;
}

}  // namespace xr::integrations
