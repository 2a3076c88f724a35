#pragma once
// Home Assistant MQTT discovery documents and the state document (docs/integrations.md).
// Pure: topics and JSON text from the settings and one sample, so the tests
// can check every field Home Assistant requires without a broker.
//
// Topics (prefix = discovery_prefix, id = node_id):
//   <prefix>/<component>/xregulator_<id>/<object>/config   retained configs
//   xregulator/<id>/state                                  one JSON document
//   xregulator/<id>/availability                           online / offline (LWT)
//   xregulator/<id>/set/mode, xregulator/<id>/set/limp_home  commands (opt-in)
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/commands.h"
#include "integrations/integration_sample.h"
#include "integrations/push_message.h"

namespace xr::integrations {

struct MqttMessage {
  std::string topic;
  std::string payload;
};

struct HaTopics {
  std::string prefix, id;
  std::string state() const { return "xregulator/" + id + "/state"; }
  std::string availability() const { return "xregulator/" + id + "/availability"; }
  std::string modeCommand() const { return "xregulator/" + id + "/set/mode"; }
  std::string limpHomeCommand() const { return "xregulator/" + id + "/set/limp_home"; }
  // An incident's start and end, for the event entity (docs/integrations.md "Alarms that reach the owner").
  std::string incidentEvent() const { return "xregulator/" + id + "/incident"; }
  std::string birth() const { return prefix + "/status"; }  // Home Assistant's own online/offline
  std::string config(const std::string& component, const std::string& object) const {
    return prefix + "/" + component + "/xregulator_" + id + "/" + object + "/config";
  }
};

// What one message on a command topic asks for: a command, or why it is
// refused (a payload other than "off"/"auto" on the mode topic or "PRESS"
// on the limp-home one). nullopt and an empty `refused` for another topic.
struct HaCommandDecision {
  std::optional<CommandType> command;
  std::string refused;
};
HaCommandDecision decodeHaCommand(const HaTopics& t, std::string_view topic, std::string_view payload);

// Every retained discovery config: the sensors and binary sensors always,
// the select (off/auto) and the button (limp home) only when withCommands.
std::vector<MqttMessage> discoveryConfigs(const HaTopics& t, bool withCommands, const std::string& version);

// The state document for one sample. `incident`: the incident acting now
// (the "incident" binary sensor is ON and carries its words), or null.
std::string stateJson(const IntegrationSample& s, const IncidentWords* incident = nullptr);

// One incident edge for the event entity: event_type start|end and the words.
std::string incidentEventJson(const IncidentEdge& e, const IncidentWords& words);

// "off" when the regulator is switched off by the operator, else "auto"
// (the select's current option).
std::string regulatorModeOption(const IntegrationSample& s);

}  // namespace xr::integrations
