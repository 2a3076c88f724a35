#pragma once
// Victron GX over MQTT (issue 23): reads a battery's charge limits and state
// from Venus OS's local broker, keeps the subscription alive, refuses bad
// values, and hands the newest limits (with their freshness) to the
// BMS-limits input through a sink.
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>

#include "config/settings.h"
#include "core/inputs.h"
#include "integrations/integration_health.h"
#include "integrations/mqtt_link.h"
#include "integrations/victron_topics.h"

namespace xr::integrations {

// The newest limits from the GX. NaN / -1: not known.
struct VictronLimits {
  double cvl_v = kNoValue;  // Info/MaxChargeVoltage
  double ccl_a = kNoValue;  // Info/MaxChargeCurrent
  double soc_pct = kNoValue;
  double temp_c = kNoValue;
  int allowToCharge = -1;  // Io/AllowToCharge: 1 yes, 0 no
  double ageS = -1;        // seconds since the last accepted value (-1: none yet)
  bool stale = true;       // nothing accepted within stale_s (REASON_BMS_STALE)
};

// Called on the integrations thread with the newest limits after every
// accepted value and once a second (so staleness is seen without traffic).
using VictronLimitsSink = std::function<void(const VictronLimits&)>;

class VictronGxBridge {
 public:
  VictronGxBridge(boost::asio::io_context& io, const VictronSettings& s, VictronLimitsSink sink);
  void start();
  void stop();
  IntegrationStatus status() const;
  VictronLimits limits() const;

 private:
  void onConnected();
  void onMessage(const std::string& topic, std::string_view payload);
  void tick();
  void publishToSink();

  VictronSettings settings_;
  VictronTopics topics_;
  VictronLimitsSink sink_;
  IntegrationHealth health_;
  std::unique_ptr<MqttLink> link_;
  boost::asio::steady_timer timer_;
  mutable std::mutex m_;  // limits_ are read by the web threads
  VictronLimits limits_;
  std::chrono::steady_clock::time_point lastAccepted_{};
  std::chrono::steady_clock::time_point lastKeepalive_{};
  bool staleLogged_ = false;
};

}  // namespace xr::integrations
