#pragma once
// The small pieces every protection part shares: the per-tick event writer
// (time, the sequencer's mode, the last trip for telemetry), the trip/clear
// memory of one detector and the sustained-condition timer
// (docs/protections.md "Protections": "sustained for N s").
#include "core/events.h"
#include "core/modes.h"
#include "core/time.h"

namespace xr {

// The last protection that tripped (docs/protections.md, telemetry
// lastTripReason / lastTripTimeS).
struct LastTrip {
  Reason reason = Reason::NONE;
  TimeNs time = 0;
};

// Writes one tick's protection events, each stamped with the tick's time and
// the mode the sequencer ran last (the journal's "mode" column).
class ProtectionLog {
 public:
  ProtectionLog(EventBatch& ev, TimeNs now, FieldControlMode mode, LastTrip& trip) noexcept
      : ev_(ev), now_(now), mode_(mode), trip_(trip) {}
  void push(EventCode c, EventLevel l, Reason r, double a = 0.0, double b = 0.0,
            int detail = 0) const noexcept {
    ev_.push(makeEvent(now_, l, c, r, a, b, detail, mode_));
  }
  // Remember r as the last trip (telemetry), without an event.
  void noteTrip(Reason r) const noexcept {
    trip_.reason = r;
    trip_.time = now_;
  }
  TimeNs now() const noexcept { return now_; }

 private:
  EventBatch& ev_;         // this tick's event batch
  TimeNs now_;             // this tick's time
  FieldControlMode mode_;  // the sequencer's mode of the last decision
  LastTrip& trip_;         // the supervisor's last-trip record
};

// Trip/clear logging memory of one detector. A detector sitting on its
// threshold (noise, or a ramp that brings the value back to exactly the
// limit) must not write a trip/clear pair every tick: the trip is logged on
// the rising edge, the clear once the condition stayed false for kClearHold
// (a re-trip inside that window is the same event).
struct EventEdge {
  static constexpr TimeNs kClearHold = 1'000'000'000;
  bool logged = false;     // the trip was logged and its clear not yet
  TimeNs falseSince = -1;  // first instant the condition was false again, -1 = true
  // logTrip = false when a dedicated event (the original firmware's wording)
  // already reports the trip.
  void update(bool now, Reason r, double a, double b, const ProtectionLog& log,
              EventLevel level = EventLevel::Warning, bool logTrip = true) noexcept {
    if (now) {
      falseSince = -1;
      if (logged) return;
      logged = true;
      log.noteTrip(r);
      if (logTrip) log.push(EventCode::ProtectionTrip, level, r, a, b);
      return;
    }
    if (!logged) return;
    if (falseSince < 0) falseSince = log.now();
    if (log.now() - falseSince < kClearHold) return;
    logged = false;
    falseSince = -1;
    log.push(EventCode::ProtectionClear, EventLevel::Info, r, a, b);
  }
};

// "Condition held continuously for hold": true once it has, reset the moment
// it does not hold.
struct SustainTimer {
  TimeNs since = -1;  // first instant the condition held, -1 = not holding
  bool update(bool cond, TimeNs now, TimeNs hold) noexcept {
    if (!cond) {
      since = -1;
      return false;
    }
    if (since < 0) since = now;
    return now - since >= hold;
  }
  void reset() noexcept { since = -1; }
};

}  // namespace xr
