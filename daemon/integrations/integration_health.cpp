#include "integrations/integration_health.h"

#include <spdlog/spdlog.h>

namespace xr::integrations {

IntegrationHealth::IntegrationHealth(std::string name, const rt::WallClock& clock, bool enabled)
    : name_(std::move(name)), clock_(clock) {
  s_.name = name_;
  s_.enabled = enabled;
}

void IntegrationHealth::attempt() {
  std::lock_guard lock(m_);
  ++s_.connect_attempts;
}

void IntegrationHealth::connected() {
  std::lock_guard lock(m_);
  if (s_.connected) return;
  s_.connected = true;
  if (inOutage_) {
    const auto secs =
        std::chrono::duration_cast<std::chrono::seconds>(clock_.steadyNow() - outageSince_).count();
    spdlog::info("{}: connected again after {} s ({} attempts so far)", name_, secs, s_.connect_attempts);
  } else {
    spdlog::info("{}: connected", name_);
  }
  inOutage_ = false;
}

void IntegrationHealth::failed(const std::string& error) {
  std::lock_guard lock(m_);
  s_.last_error = error;
  s_.connected = false;
  if (inOutage_) return;  // the outage is already in the journal
  inOutage_ = true;
  outageSince_ = clock_.steadyNow();
  ++s_.outages;
  spdlog::warn("{}: {}; retrying with backoff (logged again when it is back)", name_, error);
}

void IntegrationHealth::sent(std::uint64_t n) {
  std::lock_guard lock(m_);
  s_.messages_sent += n;
}

void IntegrationHealth::received(std::uint64_t n) {
  std::lock_guard lock(m_);
  s_.messages_received += n;
}

void IntegrationHealth::dropped(std::uint64_t n) {
  std::lock_guard lock(m_);
  s_.messages_dropped += n;
}

void IntegrationHealth::refused(const std::string& why) {
  std::lock_guard lock(m_);
  ++s_.values_refused;
  const auto now = clock_.steadyNow();
  if (s_.values_refused == 1 || now - lastRefusalLog_ >= std::chrono::minutes(1)) {
    lastRefusalLog_ = now;
    spdlog::warn("{}: refused a value: {} ({} refused so far)", name_, why, s_.values_refused);
  }
}

IntegrationStatus IntegrationHealth::status() const {
  std::lock_guard lock(m_);
  return s_;
}

}  // namespace xr::integrations
