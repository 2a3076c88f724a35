// Pairing by presence (presence_pairing.h).
#include "app/presence_pairing.h"

#include <spdlog/spdlog.h>

#include <chrono>

#include "app/web_api.h"
#include "runtime/handoffs.h"
#include "web/server/web_server.h"

namespace xr::app {

bool PresenceSequence::feed(bool on, std::int64_t elapsedMs) {
  if (!known_ || on == last_) {
    known_ = true;
    last_ = on;
    return false;
  }
  last_ = on;
  edges_ = {edges_[1], edges_[2], elapsedMs};
  if (count_ < 3) ++count_;
  // Alternating transitions ending in "on": the last three are on, off, on;
  // the "off" before the first of them may have lasted hours (parked).
  if (!on || count_ < 3 || elapsedMs - edges_[0] > kPresenceSequenceMs) return false;
  count_ = 0;  // one window per sequence
  return true;
}

void PresencePairing::poll(const rt::Handoffs& handoffs, web::WebServer* server, WebApi* api) {
  const rt::RuntimeSnapshot s = handoffs.latest();
  if (s.tick == 0 || !server) return;
  const auto nowMs = std::chrono::duration_cast<std::chrono::milliseconds>(
                         std::chrono::steady_clock::now().time_since_epoch())
                         .count();
  if (!sequence_.feed(s.telemetry.ignition_on, nowMs)) return;
  server->openPresencePairingWindow(kPresenceWindowMs);
  const std::string text =
      "Pairing window opened for 2 min by the ignition turned off-on-off-on: one device "
      "may pair without a code";
  if (api)
    api->securityEvent(text);
  else
    spdlog::warn("security: {}", text);
}

}  // namespace xr::app
