#include "store/event_queue.h"

#include <algorithm>
#include <array>
#include <string_view>

namespace xr {

namespace {
// The rows a fault storm repeats: what the regulator's protections, sensors
// and buses raise by themselves. What a person did (a command, a settings
// change, a pairing, the set-up) and the store's own alarms are never
// thinned: each is kept as its own row (docs/performance.md "Storage writes").
constexpr std::array<std::string_view, 27> kThinned = {
    "ModeChanged",     "ProtectionTrip",  "ProtectionClear",     "ImmediateCut",    "CutAfterSettle",
    "LockoutStarted",  "LockoutExpired",  "StageChanged",        "FieldOn",         "FieldOff",
    "InaLatchSet",     "InaLatchCleared", "VoltageDisagreement", "TempSensorStale", "TempTaskHung",
    "AlarmOn",         "AlarmOff",        "LimpHomeActive",      "AlarmCondition",  "BatteryTempMissing",
    "BatteryTempBack", "BmsBadFrames",    "CanBusDown",          "CanBusBack",      "CanErrorFrames",
    "BmsMismatch",     "ChargingHeld"};

bool thinned(const EventRecord& e) {
  return std::find(kThinned.begin(), kThinned.end(), e.code) != kThinned.end();
}
}  // namespace

void EventQueue::push(const EventRecord& e) {
  if (opt_.repeatKept <= 0 || !thinned(e)) {
    pending_.push_back(e);
    return;
  }
  Window& w = windows_[Key{e.level, e.code, e.reason}];
  if (w.kept == 0 || ended(w, e.tMs)) {
    summarise(w);
    w = Window{};
    w.startMs = e.tMs;
  }
  if (w.kept < opt_.repeatKept) {
    ++w.kept;
    pending_.push_back(e);
    return;
  }
  if (w.repeats++ == 0) w.firstRepeatMs = e.tMs;
  w.last = e;
}

void EventQueue::summarise(Window& w) {
  if (w.repeats == 0) return;
  EventRecord s = w.last;
  s.id = 0;
  const std::int64_t minutes = std::max<std::int64_t>(1, (w.last.tMs - w.firstRepeatMs + 59'999) / 60'000);
  s.message += " [and " + std::to_string(w.repeats) + " more like it within " + std::to_string(minutes) +
               " min: counted, not stored one by one]";
  pending_.push_back(std::move(s));
  w.repeats = 0;
}

bool EventQueue::due(std::int64_t nowMs) const {
  bool waiting = !pending_.empty();
  for (const auto& [k, w] : windows_) waiting |= w.repeats > 0 && ended(w, nowMs);
  if (!waiting) return false;
  return pending_.size() >= opt_.maxPending || nowMs - lastWriteMs_ >= opt_.commitEveryMs ||
         nowMs < lastWriteMs_;
}

std::vector<EventRecord> EventQueue::take(std::int64_t nowMs, bool all) {
  for (auto it = windows_.begin(); it != windows_.end();) {
    if (all || ended(it->second, nowMs)) {
      summarise(it->second);
      it = windows_.erase(it);
    } else {
      ++it;
    }
  }
  std::vector<EventRecord> out;
  out.swap(pending_);
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.tMs < b.tMs; });
  return out;
}

}  // namespace xr
