#include "app/integrations_wiring.h"

#include <spdlog/spdlog.h>

#include "integrations/victron_bms_hop.h"

namespace xr::app {

std::unique_ptr<integrations::IntegrationsService> startIntegrations(const Settings& s,
                                                                     rt::Handoffs& handoffs,
                                                                     StoreService* store,
                                                                     const rt::WallClock& clock,
                                                                     integrations::IncidentSource incidents) {
  // Commands from the network take the same queue as POST /api/commands; the
  // regulator applies or refuses them between ticks and its event says which.
  auto sink = [&handoffs](const Command& c, const std::string& source) {
    const bool queued = handoffs.submitCommand(c);
    spdlog::info("command '{}' from {}: {}", toString(c.type), source,
                 queued ? "queued for the regulator" : "refused: command queue full");
  };
  integrations::TokenStore tokens;
  if (store) {
    tokens.load = [store](const std::string& key) { return store->loadValue(key); };
    tokens.save = [store](const std::string& key, const std::string& value) { store->saveValue(key, value); };
  }
  // The GX's battery limits go to the control law through Handoffs::bms,
  // like a BMS on CAN (the loader refuses both at once: one writer).
  integrations::VictronLimitsSink bmsLimits;
  if (s.integrations.victron.enabled) {
    auto hop = std::make_shared<integrations::VictronBmsHop>(handoffs);
    bmsLimits = [hop](const integrations::VictronLimits& l) { (*hop)(l); };
    // Configured, not heard yet: followed from now on, stale if silent.
    BmsLimits configured;
    configured.source = BmsSource::VictronGx;
    handoffs.bms.store(configured);
    if (handoffs.acceptedParams().BmsLimitsEnabled)
      spdlog::info("victron: following the GX's battery limits (stale after BmsStaleS without them)");
    else
      spdlog::warn(
          "victron: monitor only (BmsLimitsEnabled = 0): the GX's battery limits are shown, not followed");
  }
  try {
    auto service = std::make_unique<integrations::IntegrationsService>(
        s.integrations, handoffs, sink, tokens, XR_VERSION_STRING, clock, bmsLimits, std::move(incidents));
    if (!service->anyEnabled()) return nullptr;
    service->start();
    return service;
  } catch (const std::exception& e) {
    // A convenience that cannot start (a TLS file missing, ...) leaves the
    // regulator running without it, loudly.
    spdlog::error("integrations cannot start: {}: the regulator runs without them", e.what());
    return nullptr;
  }
}

std::function<std::vector<web::IntegrationState>()> integrationsView(
    const integrations::IntegrationsService* service) {
  return [service] {
    std::vector<web::IntegrationState> out;
    if (!service) return out;
    for (const auto& s : service->statuses()) {
      web::IntegrationState w;
      w.name = s.name;
      w.enabled = s.enabled;
      w.connected = s.connected;
      w.last_error = s.last_error;
      w.messages_sent = s.messages_sent;
      w.messages_received = s.messages_received;
      w.messages_dropped = s.messages_dropped;
      w.values_refused = s.values_refused;
      w.outages = s.outages;
      w.values = s.values;
      w.texts = s.texts;
      out.push_back(std::move(w));
    }
    return out;
  };
}

}  // namespace xr::app
