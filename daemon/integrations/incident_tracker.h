#pragma once
// Incidents for the owner away from the boat (docs/integrations.md "Alarms"):
// the same grouping as the dashboard's Events page (web/www/js/events.js
// groupIncidents), so a push, Home Assistant and the page tell one story. A
// protection's trip (or a sensor gone, the INA228 latch) opens an incident;
// what follows it (the cut, the buzzer, the cooldown, the clears) belongs to
// it; it ends once every protection it tripped has cleared and nothing new
// tripped for kIncidentSettleS. Pure: events and wall-clock seconds in,
// start and end edges out.
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/events.h"

namespace xr::integrations {

// After the last clear, a trip within this many seconds is the same
// incident (events.js SETTLE_S): a fault hovering at its threshold is one
// alarm, not one push per flicker.
inline constexpr double kIncidentSettleS = 5.0;

struct Incident {
  std::uint64_t id = 0;          // the wall-clock ms of its first event: unique, and the same on every retry
  Reason reason = Reason::NONE;  // the worst reason seen (it names the incident)
  EventLevel level = EventLevel::Warning;
  double startS = 0.0;  // unix seconds
  double endS = 0.0;    // unix seconds; 0 while open
  // What the regulator did, as the dashboard says it ("cut the field at once, sounded the alarm").
  bool cut = false, rampedCut = false, fieldOff = false, lockout = false, alarm = false, resumed = false;
};

struct IncidentEdge {
  bool start = true;  // false: the end
  Incident incident;
};

class IncidentTracker {
 public:
  // One event, stamped on the one wall clock: the edges it makes, oldest
  // first (the end of a settled incident, then the start of the next).
  std::vector<IncidentEdge> onEvent(const Event& e, double wallS);
  // The end, once the incident has been clear for kIncidentSettleS.
  std::optional<IncidentEdge> poll(double wallS);
  const std::optional<Incident>& open() const { return open_; }

 private:
  std::optional<Incident> open_;
  std::set<Reason> tripped_;
  double clearedAt_ = -1.0;  // when the last tripped reason cleared; -1 while one acts
  double lastAt_ = 0.0;      // the incident's last event
  bool fieldOffNow_ = false;
};

// "The regulator cut the field at once, sounded the alarm, resumed charging." (empty when it did nothing)
std::string whatTheRegulatorDid(const Incident& i);

}  // namespace xr::integrations
