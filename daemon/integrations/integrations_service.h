#pragma once
// The integrations' own thread (docs/integrations.md): one Asio io_context, off the
// control thread, SCHED_OTHER. Each enabled integration runs on it and reads
// the telemetry seqlock; nothing here can delay a control tick.
#include <boost/asio/io_context.hpp>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "config/settings.h"
#include "integrations/home_assistant.h"
#include "integrations/incident_watch.h"
#include "integrations/integration_health.h"
#include "integrations/push_notifier.h"
#include "integrations/signalk_client.h"
#include "integrations/victron_gx.h"
#include "integrations/weather_client.h"
#include "runtime/handoffs.h"
#include "runtime/wall_clock.h"

namespace xr::integrations {

class IntegrationsService {
 public:
  // `incidents`: the event feed for the push and Home Assistant's incident
  // sensor; without a feed there are no incidents to tell.
  IntegrationsService(const IntegrationsSettings& s, rt::Handoffs& handoffs, CommandSink commands,
                      TokenStore tokens, std::string version, const rt::WallClock& clock,
                      VictronLimitsSink bmsLimits = {}, IncidentSource incidents = {});
  ~IntegrationsService();
  IntegrationsService(const IntegrationsService&) = delete;
  IntegrationsService& operator=(const IntegrationsService&) = delete;

  bool anyEnabled() const { return ha_ || signalk_ || victron_ || weather_ || push_; }
  void start();
  void stop();  // idempotent; says "offline" to the brokers it is connected to

  // Every integration, enabled or not, for /api/system and /metrics.
  std::vector<IntegrationStatus> statuses() const;

 private:
  IntegrationsSettings settings_;
  boost::asio::io_context io_;
  SignalKPosition signalkPosition_;  // navigation.position, for the forecast
  std::unique_ptr<HomeAssistantBridge> ha_;
  std::unique_ptr<SignalKClient> signalk_;
  std::unique_ptr<VictronGxBridge> victron_;
  std::unique_ptr<WeatherClient> weather_;
  std::unique_ptr<PushNotifier> push_;
  std::unique_ptr<IncidentWatch> incidents_;
  std::thread thread_;
  bool running_ = false;
};

}  // namespace xr::integrations
