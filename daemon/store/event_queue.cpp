#include "store/event_queue.h"

#include <algorithm>
#include <array>

#include "core/events.h"

namespace xr {

namespace {
// The rows a fault storm repeats: what the regulator's protections, sensors
// and buses raise by themselves. What a person did (a command, a settings
// change, a pairing, the set-up) and the store's own alarms are never
// thinned: each is kept as its own row (docs/performance.md "Storage writes").
constexpr std::array kThinned = {EventCode::ModeChanged,
                                 EventCode::ProtectionTrip,
                                 EventCode::ProtectionClear,
                                 EventCode::ImmediateCut,
                                 EventCode::CutAfterSettle,
                                 EventCode::LockoutStarted,
                                 EventCode::LockoutExpired,
                                 EventCode::StageChanged,
                                 EventCode::FieldOn,
                                 EventCode::FieldOff,
                                 EventCode::InaLatchSet,
                                 EventCode::InaLatchCleared,
                                 EventCode::VoltageDisagreement,
                                 EventCode::TempSensorStale,
                                 EventCode::TempTaskHung,
                                 EventCode::AlarmOn,
                                 EventCode::AlarmOff,
                                 EventCode::LimpHomeActive,
                                 EventCode::AlarmCondition,
                                 EventCode::BatteryTempMissing,
                                 EventCode::BatteryTempBack,
                                 EventCode::BmsBadFrames,
                                 EventCode::CanBusDown,
                                 EventCode::CanBusBack,
                                 EventCode::CanErrorFrames,
                                 EventCode::BmsMismatch,
                                 EventCode::ChargingHeld};

// The stored code is the event's name (core/events.h toString).
bool thinned(const EventRecord& e) {
  return std::any_of(kThinned.begin(), kThinned.end(), [&](EventCode c) { return toString(c) == e.code; });
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
