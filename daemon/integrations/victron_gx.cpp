#include "integrations/victron_gx.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "integrations/clock_wait.h"

namespace xr::integrations {

namespace {
using namespace std::chrono_literals;
// Venus drops a subscriber's topics 60 s after its last keepalive.
constexpr auto kKeepalivePeriod = 30s;
// After the first keepalive (which makes Venus publish every value once),
// ask it not to republish everything each time.
constexpr const char* kKeepaliveQuiet = R"({"keepalive-options": ["suppress-republish"]})";
constexpr VictronField kFields[] = {VictronField::MaxChargeVoltage, VictronField::MaxChargeCurrent,
                                    VictronField::Soc, VictronField::TemperatureC,
                                    VictronField::AllowToCharge};
}  // namespace

VictronGxBridge::VictronGxBridge(boost::asio::io_context& io, const VictronSettings& s,
                                 VictronLimitsSink sink, StaleSeconds staleS, const rt::WallClock& clock)
    : settings_(s),
      clock_(clock),
      topics_{s.portal_id, s.battery_instance},
      sink_(std::move(sink)),
      staleS_(std::move(staleS)),
      health_("victron", clock),
      timer_(io) {
  MqttOptions o;
  o.host = s.host;
  o.port = s.port;
  o.clientId = "xregulator_victron_" + s.portal_id;
  link_ = std::make_unique<MqttLink>(io, o, health_, clock_);
}

void VictronGxBridge::start() {
  link_->start([this] { onConnected(); },
               [this](const std::string& t, std::string_view p, bool) { onMessage(t, p); });
  tick();
}

void VictronGxBridge::stop() {
  timer_.cancel();
  link_->stop();
}

void VictronGxBridge::onConnected() {
  for (auto f : kFields) link_->subscribe(topics_.topic(f));
  link_->publish(topics_.keepalive(), "", false);  // every value once, now
  lastKeepalive_ = std::chrono::steady_clock::now();
}

void VictronGxBridge::onMessage(const std::string& topic, std::string_view payload) {
  const auto r = decodeVictron(topics_, topic, payload);
  if (!r) return;
  if (!r->refused.empty()) {
    health_.refused(r->refused);  // never reaches the limits
    return;
  }
  const bool limit = r->field == VictronField::MaxChargeVoltage || r->field == VictronField::MaxChargeCurrent;
  {
    std::lock_guard lock(m_);
    const double v = r->known ? r->value : kNoValue;
    switch (r->field) {
      case VictronField::MaxChargeVoltage:
        limits_.cvl_v = v;
        break;
      case VictronField::MaxChargeCurrent:
        limits_.ccl_a = v;
        break;
      case VictronField::Soc:
        limits_.soc_pct = v;
        break;
      case VictronField::TemperatureC:
        limits_.temp_c = v;
        break;
      case VictronField::AllowToCharge:
        limits_.allowToCharge = r->known ? static_cast<int>(v) : -1;
        break;
    }
    // Only a limit that is known refreshes: a null or a vanished battery
    // leaves the old arrival time, so the limits go stale after BmsStaleS.
    if (limit && r->known) {
      lastLimits_ = clock_.steadyNow();
      ++limits_.limitUpdates;
      limits_.stale = false;
      limits_.ageS = 0;
    }
  }
  if (r->gone && !goneLogged_) {
    goneLogged_ = true;
    spdlog::warn("victron: battery {} left the GX (empty payload): its limits are unknown",
                 settings_.battery_instance);
  } else if (r->known) {
    goneLogged_ = false;
  }
  if (limit && r->known && staleLogged_) {
    staleLogged_ = false;
    spdlog::info("victron: battery limits fresh again");
  }
  publishToSink();
}

// Venus publishes a value only when it changes; a read request makes it
// publish the current one, so a steady CCL still arrives on every poll and a
// GX (or battery) that stopped answering goes stale.
void VictronGxBridge::requestLimits() {
  for (auto f : kFields) link_->publish(topics_.readRequest(f), "", false);
}

void VictronGxBridge::tick() {
  const auto now = clock_.steadyNow();
  const double staleS = staleS_ ? staleS_() : 10.0;
  if (link_->connected()) {
    // Venus forgets a subscriber after 60 s of its own time: real time.
    const auto realNow = std::chrono::steady_clock::now();
    if (realNow - lastKeepalive_ >= kKeepalivePeriod) {
      link_->publish(topics_.keepalive(), kKeepaliveQuiet, false);
      lastKeepalive_ = realNow;
    }
    requestLimits();
  }
  bool stale = true;
  {
    std::lock_guard lock(m_);
    if (lastLimits_ != std::chrono::steady_clock::time_point{}) {
      limits_.ageS = std::chrono::duration<double>(now - lastLimits_).count();
      limits_.stale = limits_.ageS > staleS;
      stale = limits_.stale;
    }
  }
  if (stale && lastLimits_ != std::chrono::steady_clock::time_point{} && !staleLogged_) {
    staleLogged_ = true;
    spdlog::warn("victron: no battery limits for {} s: stale (REASON_BMS_STALE)", staleS);
  }
  publishToSink();
  // At least four polls within BmsStaleS, so one lost answer is not stale;
  // never faster than 4 Hz (five small publishes each).
  const auto period = std::chrono::duration<double>(std::clamp(staleS / 4.0, 0.25, 1.0));
  afterOnClock(clock_, timer_, std::chrono::duration_cast<ClockDuration>(period), [this] { tick(); });
}

void VictronGxBridge::publishToSink() {
  if (sink_) sink_(limits());
}

VictronLimits VictronGxBridge::limits() const {
  std::lock_guard lock(m_);
  return limits_;
}

IntegrationStatus VictronGxBridge::status() const {
  IntegrationStatus s = health_.status();
  const VictronLimits l = limits();
  s.values = {{"bms_cvl_v", l.cvl_v},
              {"bms_ccl_a", l.ccl_a},
              {"bms_soc_pct", l.soc_pct},
              {"battery_temp_c", l.temp_c},
              {"allow_to_charge", static_cast<double>(l.allowToCharge)},
              {"age_s", l.ageS},
              {"stale", l.stale ? 1.0 : 0.0},
              {"limit_updates", static_cast<double>(l.limitUpdates)}};
  return s;
}

}  // namespace xr::integrations
