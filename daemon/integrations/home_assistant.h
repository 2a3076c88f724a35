#pragma once
// Home Assistant through MQTT discovery (docs/integrations.md): announces the device
// (retained configs), publishes the state document at state_rate_hz, keeps
// availability through the broker's last will, re-announces when Home
// Assistant says "online" on <prefix>/status, and takes off/auto and limp
// home only when commands are enabled and the broker needs credentials.
//
// Commands are actions, never states (docs/security.md "MQTT commands"): a
// retained command is ignored and cleared, and commands stay off until an
// anonymous test connection has been refused by the broker, because the
// broker cannot tell us who published a message.
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "config/settings.h"
#include "core/commands.h"
#include "integrations/ha_discovery.h"
#include "integrations/integration_health.h"
#include "integrations/mqtt_link.h"
#include "integrations/push_message.h"
#include "runtime/handoffs.h"

namespace xr::integrations {

// Hands an operator command to the regulator and logs it like an HTTP one;
// `source` says where it came from ("Home Assistant (MQTT)").
using CommandSink = std::function<void(const Command& c, const std::string& source)>;

class HomeAssistantBridge {
 public:
  HomeAssistantBridge(boost::asio::io_context& io, const MqttSettings& s, const rt::Handoffs& handoffs,
                      CommandSink commands, std::string version, const rt::WallClock& clock);
  void start();
  void stop();
  IntegrationStatus status() const { return health_.status(); }
  // On the io_context's thread: an incident started or ended; the state
  // goes out at once and the event entity fires.
  void onIncident(const IncidentEdge& e);

 private:
  void announce();
  void publishState();
  void onMessage(const std::string& topic, std::string_view payload, bool retained);
  void onCommand(const std::string& topic, std::string_view payload);
  void checkAnonymousAccess();
  void anonymousRefused();
  void anonymousAccepted();
  void tick();

  boost::asio::io_context& io_;
  const rt::WallClock& clock_;  // the state period runs on it (clock_wait.h)
  MqttSettings settings_;
  const rt::Handoffs& handoffs_;
  CommandSink commands_;
  std::string version_;
  HaTopics topics_;
  bool withCommands_;          // the configuration asks for commands, with credentials
  bool commandsLive_ = false;  // ...and the broker has refused an anonymous client
  IntegrationHealth health_;
  IntegrationHealth probeHealth_;
  std::unique_ptr<MqttLink> link_;
  std::unique_ptr<MqttLink> anonymousProbe_;
  boost::asio::steady_timer timer_;
  std::uint64_t announcements_ = 0;
  std::optional<IncidentWords> incident_;  // the incident acting now
};

}  // namespace xr::integrations
