#pragma once
// The state of one integration (docs/integrations.md): connected or not, the last error,
// what it sent and what it refused. Written by the integrations thread, read
// by the web threads for /api/system and /metrics; the control thread never
// touches it.
//
// A dead server is logged once per outage, not once per attempt: the first
// failure after a connection (or at start) logs, the retries that follow are
// only counted, and the reconnection logs how long the outage lasted.
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

#include "runtime/wall_clock.h"

namespace xr::integrations {

struct IntegrationStatus {
  std::string name;  // "signalk", "mqtt", "victron"
  bool enabled = false;
  bool connected = false;
  std::string last_error;  // empty when none since start
  std::uint64_t messages_sent = 0;
  std::uint64_t messages_received = 0;
  std::uint64_t messages_dropped = 0;  // replaced by a newer one while the link was busy or down
  std::uint64_t values_refused = 0;    // bad input from the server (string, NaN, absurd)
  std::uint64_t outages = 0;           // connections lost or never made
  std::uint64_t connect_attempts = 0;
  std::map<std::string, double> values;      // what the integration reads (Victron limits); NaN = none
  std::map<std::string, std::string> texts;  // what it reads that is a word (the forecast's position source)
};

class IntegrationHealth {
 public:
  // clock: the one clock below the core (outage lengths, the refusal log's pace).
  IntegrationHealth(std::string name, const rt::WallClock& clock, bool enabled = true);

  void attempt();                         // a connection attempt starts
  void connected();                       // logs the first connection and each recovery
  void failed(const std::string& error);  // logs once per outage
  void sent(std::uint64_t n = 1);
  void received(std::uint64_t n = 1);
  void dropped(std::uint64_t n = 1);
  // Bad input: counted always, logged at most once a minute with its reason.
  void refused(const std::string& why);

  IntegrationStatus status() const;
  const std::string& name() const { return name_; }

 private:
  mutable std::mutex m_;
  const std::string name_;
  const rt::WallClock& clock_;
  IntegrationStatus s_;
  bool inOutage_ = false;
  std::chrono::steady_clock::time_point outageSince_{};
  std::chrono::steady_clock::time_point lastRefusalLog_{};
};

}  // namespace xr::integrations
