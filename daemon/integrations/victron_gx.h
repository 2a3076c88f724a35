#pragma once
// Victron GX over MQTT (docs/integrations.md): reads a battery's charge limits and state
// from Venus OS's local broker, keeps the subscription alive, refuses bad
// values, and hands the newest limits (with their freshness) to the
// BMS-limits input through a sink.
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>

#include "config/settings.h"
#include "core/inputs.h"
#include "integrations/integration_health.h"
#include "integrations/mqtt_link.h"
#include "integrations/victron_topics.h"

namespace xr::integrations {

// The newest limits from the GX. NaN / -1: not known (Venus's null, or the
// battery service gone).
struct VictronLimits {
  double cvl_v = kNoValue;  // Info/MaxChargeVoltage
  double ccl_a = kNoValue;  // Info/MaxChargeCurrent
  double soc_pct = kNoValue;
  double temp_c = kNoValue;
  int allowToCharge = -1;  // Io/AllowToCharge: 1 yes, 0 no
  // Freshness is that of the limits (a known CVL or CCL), not of SoC or
  // temperature: a GX that still sends SoC but no limits is not followed.
  std::uint64_t limitUpdates = 0;  // known CVL/CCL values accepted so far
  double ageS = -1;                // seconds since the last of them (-1: none yet)
  bool stale = true;               // none within BmsStaleS (REASON_BMS_STALE)
};

// Called on the integrations thread with the newest limits after every
// accepted value and on every poll (so staleness is seen without traffic).
using VictronLimitsSink = std::function<void(const VictronLimits&)>;
// The staleness limit in seconds (the BmsStaleS parameter, which the
// dashboard may change while running).
using StaleSeconds = std::function<double()>;

class VictronGxBridge {
 public:
  VictronGxBridge(boost::asio::io_context& io, const VictronSettings& s, VictronLimitsSink sink,
                  StaleSeconds staleS, const rt::WallClock& clock);
  void start();
  void stop();
  IntegrationStatus status() const;
  VictronLimits limits() const;

 private:
  void onConnected();
  void onMessage(const std::string& topic, std::string_view payload);
  void tick();
  void requestLimits();
  void publishToSink();

  VictronSettings settings_;
  const rt::WallClock& clock_;  // staleness and the poll period run on it (clock_wait.h)
  VictronTopics topics_;
  VictronLimitsSink sink_;
  StaleSeconds staleS_;
  IntegrationHealth health_;
  std::unique_ptr<MqttLink> link_;
  boost::asio::steady_timer timer_;
  mutable std::mutex m_;  // limits_ are read by the web threads
  VictronLimits limits_;
  std::chrono::steady_clock::time_point lastLimits_{};     // last known CVL/CCL accepted
  std::chrono::steady_clock::time_point lastKeepalive_{};  // real time: Venus's own deadline
  bool staleLogged_ = false;
  bool goneLogged_ = false;
};

}  // namespace xr::integrations
