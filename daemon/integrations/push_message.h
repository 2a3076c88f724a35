#pragma once
// What one push says (docs/integrations.md "Alarms that reach the owner"):
// an incident's start or end as a JSON document or as plain text for push
// services that show the body as it is (ntfy and similar). Pure: the
// incident, the regulator's name and the format in; the request's body and
// headers out, so the tests read every word without a server.
#include <string>
#include <utility>
#include <vector>

#include "integrations/incident_tracker.h"

namespace xr::integrations {

struct PushMessage {
  std::uint64_t incidentId = 0;
  bool start = true;
  std::string contentType;
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;  // besides Host, User-Agent, Content-Type
};

// The words the owner reads, shared by the push and Home Assistant.
struct IncidentWords {
  std::string title;             // "Alternator far too hot"
  std::string whatHappened;      // the meaning; at the end also what the regulator did and how long it lasted
  std::string whatToDo;          // the dashboard's "What to do"
  std::string severity;          // warning | error | critical
  std::string startIso, endIso;  // UTC, "2026-12-06T10:05:11Z"; endIso empty while open
};
IncidentWords incidentWords(const IncidentEdge& e);

// format: "json" or "text". The JSON keys: event (start|end), incident_id,
// title, what_happened, what_to_do, regulator, severity, reason, start, end
// (null while open), duration_s (null while open).
PushMessage pushMessage(const IncidentEdge& e, const std::string& regulator, const std::string& format);

}  // namespace xr::integrations
