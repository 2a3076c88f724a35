#include "integrations/integrations_service.h"

#include <pthread.h>
#include <spdlog/spdlog.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/post.hpp>
#include <future>

namespace xr::integrations {

IntegrationsService::IntegrationsService(const IntegrationsSettings& s, rt::Handoffs& handoffs,
                                         CommandSink commands, TokenStore tokens, std::string version,
                                         const rt::WallClock& clock, VictronLimitsSink bmsLimits,
                                         IncidentSource incidents)
    : settings_(s) {
  if (s.mqtt.enabled)
    ha_ = std::make_unique<HomeAssistantBridge>(io_, s.mqtt, handoffs, commands, version, clock);
  if (s.signalk.enabled)
    signalk_ = std::make_unique<SignalKClient>(io_, s.signalk, handoffs, std::move(tokens), clock,
                                               s.weather.enabled ? &signalkPosition_ : nullptr);
  if (s.victron.enabled) {
    // One staleness limit for every BMS source: the BmsStaleS parameter.
    victron_ = std::make_unique<VictronGxBridge>(
        io_, s.victron, std::move(bmsLimits), [&handoffs] { return handoffs.acceptedParams().BmsStaleS; },
        clock);
  }
  if (s.weather.enabled)
    weather_ = std::make_unique<WeatherClient>(io_, s.weather, handoffs, commands, clock,
                                               signalk_ ? &signalkPosition_ : nullptr);
  if (!s.notify.url.empty()) push_ = std::make_unique<PushNotifier>(io_, s.notify, s.notify.name, clock);
  // Incidents for whoever tells the owner (docs/integrations.md "Alarms that reach the owner").
  if (incidents.feed && incidents.wallNow && (push_ || ha_)) {
    incidents_ = std::make_unique<IncidentWatch>(io_, std::move(incidents));
    if (push_) incidents_->addListener([p = push_.get()](const IncidentEdge& e) { p->notify(e); });
    if (ha_) incidents_->addListener([h = ha_.get()](const IncidentEdge& e) { h->onIncident(e); });
  }
}

IntegrationsService::~IntegrationsService() { stop(); }

void IntegrationsService::start() {
  if (running_ || !anyEnabled()) return;
  running_ = true;
  if (ha_) {
    spdlog::info("mqtt: Home Assistant discovery to {}:{}{} (prefix '{}', commands {})", settings_.mqtt.host,
                 settings_.mqtt.port, settings_.mqtt.tls ? " over TLS" : "", settings_.mqtt.discovery_prefix,
                 settings_.mqtt.commands_enabled ? "enabled" : "off");
    boost::asio::post(io_, [this] { ha_->start(); });
  }
  if (victron_) {
    spdlog::info("victron: battery {} of GX {} at {}:{}", settings_.victron.battery_instance,
                 settings_.victron.portal_id, settings_.victron.host, settings_.victron.port);
    boost::asio::post(io_, [this] { victron_->start(); });
  }
  if (signalk_) {
    spdlog::info("signalk: deltas to {} at {} Hz", settings_.signalk.url, settings_.signalk.rate_hz);
    boost::asio::post(io_, [this] { signalk_->start(); });
  }
  if (weather_) {
    spdlog::info("weather: forecast from {} every {} min", settings_.weather.url,
                 settings_.weather.refresh_min);
    boost::asio::post(io_, [this] { weather_->start(); });
  }
  if (push_) {
    spdlog::info("notify: each incident's start and end to {} as {} (from '{}')", settings_.notify.url,
                 settings_.notify.format, push_->regulator());
    boost::asio::post(io_, [this] { push_->start(); });
  }
  if (incidents_) boost::asio::post(io_, [this] { incidents_->start(); });
  thread_ = std::thread([this] {
    pthread_setname_np(pthread_self(), "xr-integrations");
    auto guard = boost::asio::make_work_guard(io_);
    try {
      io_.run();
    } catch (const std::exception& e) {
      // An integration is a convenience: it ends, the regulator does not.
      spdlog::error("integrations stopped: {}", e.what());
    }
  });
}

void IntegrationsService::stop() {
  if (!running_) return;
  running_ = false;
  std::promise<void> done;
  boost::asio::post(io_, [this, &done] {
    if (ha_) ha_->stop();
    if (signalk_) signalk_->stop();
    if (victron_) victron_->stop();
    if (weather_) weather_->stop();
    if (incidents_) incidents_->stop();
    if (push_) push_->stop();
    done.set_value();
  });
  if (!io_.stopped()) done.get_future().wait_for(std::chrono::seconds(3));
  io_.stop();
  thread_.join();
}

std::vector<IntegrationStatus> IntegrationsService::statuses() const {
  std::vector<IntegrationStatus> out;
  auto disabled = [](const char* name) {
    IntegrationStatus s;
    s.name = name;
    return s;
  };
  out.push_back(signalk_ ? signalk_->status() : disabled("signalk"));
  out.push_back(ha_ ? ha_->status() : disabled("mqtt"));
  out.push_back(victron_ ? victron_->status() : disabled("victron"));
  out.push_back(weather_ ? weather_->status() : disabled("weather"));
  out.push_back(push_ ? push_->status() : disabled("notify"));
  return out;
}

}  // namespace xr::integrations
