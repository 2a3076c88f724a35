#pragma once
// The daemon's side of the integrations (docs/integrations.md): builds the service from
// [integrations.*], hands commands from Home Assistant to the regulator (and
// logs them like the HTTP ones), and shows their state to the web API.
#include <functional>
#include <memory>
#include <vector>

#include "app/store_service.h"
#include "config/settings.h"
#include "integrations/integrations_service.h"
#include "runtime/handoffs.h"
#include "web/server/daemon_api.h"

namespace xr::app {

// Null when no integration is enabled; otherwise started. store may be null
// (a Signal K token then lasts for this run only). `incidents`: the events the
// push and Home Assistant's incident sensor tell the owner about.
std::unique_ptr<integrations::IntegrationsService> startIntegrations(
    const Settings& s, rt::Handoffs& handoffs, StoreService* store, const rt::WallClock& clock,
    integrations::IncidentSource incidents = {});

// For WebApiContext::integrations; an empty list when service is null.
std::function<std::vector<web::IntegrationState>()> integrationsView(
    const integrations::IntegrationsService* service);

}  // namespace xr::app
