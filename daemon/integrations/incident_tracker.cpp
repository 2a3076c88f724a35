#include "integrations/incident_tracker.h"

#include <cmath>
#include <vector>

namespace xr::integrations {

namespace {

// What opens an incident (events.js OPENS) and what belongs to one (CONSEQUENCES).
bool opens(EventCode c) {
  return c == EventCode::ProtectionTrip || c == EventCode::VoltageDisagreement ||
         c == EventCode::InaLatchSet || c == EventCode::TempSensorStale || c == EventCode::TempTaskHung;
}
bool belongs(EventCode c) {
  switch (c) {
    case EventCode::ModeChanged:
    case EventCode::ImmediateCut:
    case EventCode::CutAfterSettle:
    case EventCode::FieldOff:
    case EventCode::FieldOn:
    case EventCode::AlarmCondition:
    case EventCode::AlarmOn:
    case EventCode::AlarmOff:
    case EventCode::LockoutStarted:
    case EventCode::LockoutExpired:
    case EventCode::ProtectionClear:
    case EventCode::InaLatchCleared:
      return true;
    default:
      return opens(c);
  }
}
// A consequence further than this from the incident's last event is a new
// story (events.js JOIN_S): the longest cooldown is minutes, not an hour.
constexpr double kJoinS = 600.0;

}  // namespace

std::vector<IncidentEdge> IncidentTracker::onEvent(const Event& e, double wallS) {
  std::vector<IncidentEdge> out;
  // A settled incident ends before a new trip opens the next; a gap this
  // long with a protection still tripped ends the story without its clear.
  if (open_ && clearedAt_ >= 0 && wallS - clearedAt_ > kIncidentSettleS)
    if (auto end = poll(wallS)) out.push_back(*end);
  if (open_ && wallS - lastAt_ > kJoinS)
    if (auto end = poll(lastAt_ + kIncidentSettleS + kJoinS + 1.0)) out.push_back(*end);
  if (open_ && belongs(e.code)) {
    lastAt_ = wallS;
    Incident& i = *open_;
    if (e.code == EventCode::ProtectionTrip && e.reason != Reason::NONE) tripped_.insert(e.reason);
    if (e.code == EventCode::ProtectionClear) tripped_.erase(e.reason);
    if (e.code == EventCode::InaLatchCleared) tripped_.erase(Reason::REASON_INA_OVERVOLTAGE);
    if (e.reason != Reason::NONE && e.level > i.level) {
      i.level = e.level;
      i.reason = e.reason;
    }
    if (i.reason == Reason::NONE && e.reason != Reason::NONE) i.reason = e.reason;
    i.cut = i.cut || e.code == EventCode::ImmediateCut;
    i.rampedCut = i.rampedCut || e.code == EventCode::CutAfterSettle;
    i.lockout = i.lockout || e.code == EventCode::LockoutStarted;
    i.alarm = i.alarm || e.code == EventCode::AlarmOn;
    if (e.code == EventCode::FieldOff) i.fieldOff = fieldOffNow_ = true;
    if (e.code == EventCode::FieldOn) {
      i.resumed = fieldOffNow_;
      fieldOffNow_ = false;
    }
    if (opens(e.code))
      clearedAt_ = -1.0;
    else if (tripped_.empty() && clearedAt_ < 0 &&
             (e.code == EventCode::ProtectionClear || e.code == EventCode::InaLatchCleared))
      clearedAt_ = wallS;
    return out;
  }
  if (!opens(e.code) || open_) return out;
  Incident i;
  i.id = static_cast<std::uint64_t>(std::llround(wallS * 1000.0));
  i.reason = e.reason;
  i.level = e.level;
  i.startS = wallS;
  open_ = i;
  tripped_.clear();
  if (e.reason != Reason::NONE) tripped_.insert(e.reason);
  clearedAt_ = -1.0;
  lastAt_ = wallS;
  fieldOffNow_ = false;
  out.push_back(IncidentEdge{true, i});
  return out;
}

std::optional<IncidentEdge> IncidentTracker::poll(double wallS) {
  if (!open_) return std::nullopt;
  const bool settled = clearedAt_ >= 0 && wallS - clearedAt_ >= kIncidentSettleS;
  const bool forgotten = wallS - lastAt_ > kJoinS + kIncidentSettleS;
  if (!settled && !forgotten) return std::nullopt;
  Incident i = *open_;
  i.endS = settled ? clearedAt_ : lastAt_;
  open_.reset();
  tripped_.clear();
  clearedAt_ = -1.0;
  return IncidentEdge{false, i};
}

std::string whatTheRegulatorDid(const Incident& i) {
  std::vector<const char*> did;
  if (i.cut)
    did.push_back("cut the field at once");
  else if (i.rampedCut)
    did.push_back("ramped the field down and cut it");
  else if (i.fieldOff)
    did.push_back("switched the field off");
  if (i.lockout) did.push_back("waited out a cooldown");
  if (i.alarm) did.push_back("sounded the alarm");
  if (i.resumed) did.push_back("resumed charging");
  if (did.empty()) return {};
  std::string s = "The regulator";
  for (std::size_t k = 0; k < did.size(); ++k) s += std::string(k ? ", " : " ") + did[k];
  return s + ".";
}

}  // namespace xr::integrations
