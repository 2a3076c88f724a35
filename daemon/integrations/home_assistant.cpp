#include "integrations/home_assistant.h"

#include <spdlog/spdlog.h>

#include <chrono>

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
                                         std::string version)
    : io_(io),
      settings_(s),
      handoffs_(handoffs),
      commands_(std::move(commands)),
      version_(std::move(version)),
      topics_{s.discovery_prefix, s.node_id},
      // The loader refuses commands without credentials; this is the second lock.
      withCommands_(s.commands_enabled && !s.username.empty() && !s.password.empty()),
      health_("mqtt"),
      timer_(io) {
  link_ = std::make_unique<MqttLink>(io_, optionsFor(s, topics_), health_);
}

void HomeAssistantBridge::start() {
  link_->start([this] { announce(); }, [this](const std::string& t, std::string_view p) { onMessage(t, p); });
  tick();
}

void HomeAssistantBridge::stop() {
  timer_.cancel();
  link_->stop(topics_.availability(), "offline");
}

void HomeAssistantBridge::announce() {
  ++announcements_;
  for (const auto& m : discoveryConfigs(topics_, withCommands_, version_))
    link_->publish(m.topic, m.payload, true, 1);
  link_->publish(topics_.availability(), "online", true, 1);
  link_->subscribe(topics_.birth());
  if (withCommands_) {
    link_->subscribe(topics_.modeCommand());
    link_->subscribe(topics_.limpHomeCommand());
  }
  publishState();
}

void HomeAssistantBridge::publishState() {
  const IntegrationSample s = sampleOf(handoffs_.latest());
  if (!s.valid) return;
  link_->publish(topics_.state(), stateJson(s), false);
}

void HomeAssistantBridge::tick() {
  if (link_->connected()) publishState();
  timer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(1.0 / settings_.state_rate_hz)));
  timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) tick();
  });
}

void HomeAssistantBridge::onMessage(const std::string& topic, std::string_view payload) {
  if (topic == topics_.birth()) {
    // Home Assistant restarted and lost the non-retained state: announce again.
    if (payload == "online") announce();
    return;
  }
  if (!withCommands_) return;  // never subscribed; a stray message changes nothing
  const std::string source = "Home Assistant (MQTT " + settings_.host + ")";
  if (topic == topics_.modeCommand()) {
    Command c;
    if (payload == "off") {
      c.type = CommandType::Off;
    } else if (payload == "auto") {
      c.type = CommandType::Auto;
    } else {
      health_.refused("mode command '" + std::string(payload.substr(0, 32)) + "' is not off or auto");
      return;
    }
    commands_(c, source);
  } else if (topic == topics_.limpHomeCommand()) {
    if (payload != "PRESS") {
      health_.refused("limp home command payload is not PRESS");
      return;
    }
    Command c;
    c.type = CommandType::LimpHome;
    commands_(c, source);
  }
}

}  // namespace xr::integrations
