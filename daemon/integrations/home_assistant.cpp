#include "integrations/home_assistant.h"

#include <spdlog/spdlog.h>

#include <boost/asio/post.hpp>
#include <chrono>

#include "integrations/clock_wait.h"

namespace xr::integrations {

namespace {
MqttOptions optionsFor(const MqttSettings& s, const HaTopics& t) {
  MqttOptions o;
  o.host = s.host;
  o.port = s.port;
  o.clientId = "xregulator_" + s.node_id;
  o.username = s.username;
  o.password = s.password;
  o.tls = s.tls;
  o.caFile = s.ca_file;
  // Availability: the broker publishes "offline" (retained) for us when the
  // daemon dies without a goodbye (kill -9, power cut, network gone).
  o.willTopic = t.availability();
  o.willPayload = "offline";
  return o;
}
}  // namespace

HomeAssistantBridge::HomeAssistantBridge(boost::asio::io_context& io, const MqttSettings& s,
                                         const rt::Handoffs& handoffs, CommandSink commands,
                                         std::string version, const rt::WallClock& clock)
    : io_(io),
      clock_(clock),
      settings_(s),
      handoffs_(handoffs),
      commands_(std::move(commands)),
      version_(std::move(version)),
      topics_{s.discovery_prefix, s.node_id},
      // The loader refuses commands without credentials; this is the second lock.
      withCommands_(s.commands_enabled && !s.username.empty() && !s.password.empty()),
      health_("mqtt", clock),
      probeHealth_("mqtt anonymous check", clock),
      timer_(io) {
  link_ = std::make_unique<MqttLink>(io_, optionsFor(s, topics_), health_, clock_);
}

void HomeAssistantBridge::start() {
  link_->start([this] { announce(); }, [this](const std::string& t, std::string_view p,
                                              bool retained) { onMessage(t, p, retained); });
  if (withCommands_) checkAnonymousAccess();
  tick();
}

// The broker does not say who published a message, so a command is only as
// trusted as the least trusted client that may publish on its topic. A
// broker that lets anyone in without a password lets anyone send commands
// (unless its ACLs forbid it, which we cannot see): commands stay off until
// a client with no credentials has been refused (docs/security.md).
void HomeAssistantBridge::checkAnonymousAccess() {
  MqttOptions o = optionsFor(settings_, topics_);
  o.clientId = "xregulator_" + settings_.node_id + "_anonymous_check";
  o.username.clear();
  o.password.clear();
  o.willTopic.clear();
  anonymousProbe_ = std::make_unique<MqttLink>(io_, o, probeHealth_, clock_);
  anonymousProbe_->start([this] { boost::asio::post(io_, [this] { anonymousAccepted(); }); }, {},
                         [this](int) { boost::asio::post(io_, [this] { anonymousRefused(); }); });
}

void HomeAssistantBridge::anonymousRefused() {
  if (!anonymousProbe_ || commandsLive_) return;
  anonymousProbe_->stop();
  commandsLive_ = true;
  spdlog::info("mqtt: the broker refuses clients without credentials; commands from Home Assistant are on");
  if (link_->connected()) announce();
}

void HomeAssistantBridge::anonymousAccepted() {
  if (!anonymousProbe_) return;
  anonymousProbe_->stop();
  health_.refused("the broker accepts clients without credentials");
  spdlog::error(
      "mqtt: the broker at {}:{} accepts clients without a user name, so anyone on its network could "
      "send commands; MQTT commands stay OFF. Set allow_anonymous false and ACLs on the broker "
      "(docs/security.md \"MQTT commands\")",
      settings_.host, settings_.port);
}

void HomeAssistantBridge::stop() {
  timer_.cancel();
  if (anonymousProbe_) anonymousProbe_->stop();
  link_->stop(topics_.availability(), "offline");
}

void HomeAssistantBridge::announce() {
  ++announcements_;
  for (const auto& m : discoveryConfigs(topics_, commandsLive_, version_))
    link_->publish(m.topic, m.payload, true, 1);
  link_->publish(topics_.availability(), "online", true, 1);
  link_->subscribe(topics_.birth());
  if (commandsLive_) {
    link_->subscribe(topics_.modeCommand());
    link_->subscribe(topics_.limpHomeCommand());
  }
  publishState();
}

void HomeAssistantBridge::publishState() {
  const IntegrationSample s = sampleOf(handoffs_.latest(), {handoffs_.setUp.load(), ""});
  if (!s.valid) return;
  link_->publish(topics_.state(), stateJson(s, incident_ ? &*incident_ : nullptr), false);
}

void HomeAssistantBridge::onIncident(const IncidentEdge& e) {
  if (e.start)
    incident_ = incidentWords(e);
  else
    incident_.reset();
  if (!link_->connected()) return;  // the next state after the reconnect says where it stands
  // Not retained: an event is a moment; a new subscriber must not see an old one fire.
  link_->publish(topics_.incidentEvent(), incidentEventJson(e, incidentWords(e)), false, 1);
  publishState();
}

void HomeAssistantBridge::tick() {
  if (link_->connected()) publishState();
  afterOnClock(
      clock_, timer_,
      std::chrono::duration_cast<ClockDuration>(std::chrono::duration<double>(1.0 / settings_.state_rate_hz)),
      [this] { tick(); });
}

void HomeAssistantBridge::onMessage(const std::string& topic, std::string_view payload, bool retained) {
  if (topic == topics_.birth()) {
    // Home Assistant restarted and lost the non-retained state: announce again.
    if (payload == "online") announce();
    return;
  }
  if (!commandsLive_) return;  // never subscribed; a stray message changes nothing
  if (topic != topics_.modeCommand() && topic != topics_.limpHomeCommand()) return;
  if (payload.empty()) return;  // the clearing of a retained command, ours or another's
  if (retained) {
    // Stored by the broker some time ago, maybe before this start: replaying
    // it would turn an old button press into a state (limp home at every
    // start). Ignore it and delete it from the broker.
    health_.refused("retained command on " + topic + " ignored and cleared (a command is never retained)");
    link_->publish(topic, "", true, 1);
    return;
  }
  onCommand(topic, payload);
  // A retained copy published while we listened arrives live, without the
  // flag: act on it once, then delete any copy the broker kept.
  link_->publish(topic, "", true, 1);
}

void HomeAssistantBridge::onCommand(const std::string& topic, std::string_view payload) {
  const std::string source = "Home Assistant (MQTT " + settings_.host + ")";
  const HaCommandDecision d = decodeHaCommand(topics_, topic, payload);
  if (!d.refused.empty()) health_.refused(d.refused);
  if (!d.command) return;
  Command c;
  c.type = *d.command;
  commands_(c, source);
}

}  // namespace xr::integrations
