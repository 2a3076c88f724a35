#pragma once
// JSON (Boost.JSON) and Prometheus text for the web API. Pure functions of the
// daemon's plain structs: the same status text goes to GET /api/status and to
// every WebSocket client (serialised once per tick).
#include <boost/json.hpp>
#include <map>
#include <string>
#include <vector>

#include "web/server/daemon_api.h"
#include "web/server/web_server.h"

namespace xr::web {

// /api/status and the /ws frames: every CSV column (docs/operations.md) at the top level
// (visitTelemetryColumns, plus sim_* in simulation), then "control",
// "protection", "battery", "loop", "seq", "wall_time_s" and the extras' sections.
boost::json::object statusToJson(const StatusSnapshot& s);
std::string serializeStatus(const StatusSnapshot& s);

// /api/params: {"params":[{name, group, kind, unit, min, max, help, value,
// default, file, changed, overridden}...], "groups":[...]}.
// sources: name -> "default" | "profile" | "file" | "dashboard" (docs/batteries.md);
// a name missing from it is inferred from current, file and the defaults.
// profileOwned: the names a battery profile sets ("profile_owned": true).
boost::json::object paramsToJson(const Params& current, const Params& file,
                                 const std::map<std::string, std::string>& sources = {},
                                 const std::set<std::string>& profileOwned = {});

boost::json::object eventToJson(const EventRecord& e);
boost::json::object historyToJson(const HistoryResult& h);

// Prometheus text exposition format 0.0.4.
std::string metricsText(const StatusSnapshot* s, const WebServerStats& stats);

// /api/system "integrations" entries and their /metrics lines (docs/integrations.md).
boost::json::object integrationToJson(const IntegrationState& i);
std::string integrationMetrics(const std::vector<IntegrationState>& list);

// /api/system "bms" and "n2k" (docs/integrations.md).
boost::json::object canBmsToJson(const CanBmsState& b);
boost::json::object canN2kToJson(const CanN2kState& n);

// A finite number, or null (JSON has no NaN/Inf).
boost::json::value number(double v);

}  // namespace xr::web
