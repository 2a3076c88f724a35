#pragma once
// CheckpointPolicy: when the store thread saves the ledger (pure; time
// injected). The original firmware saves only at safe moments ("Critical Zone — Why NVS
// Saves Aren't Periodic"); SQLite on a non-RT thread cannot stall the control
// loop, so a periodic save is added as the bound on what a power cut loses:
//   - each time the wall clock enters a new [store] checkpoint_interval_s
//     (:00, :05, ... for 300 s), the second the chart flush and the day rows
//     are written too, so the commits share the WAL index pages each lone
//     commit dirties (docs/performance.md "Storage writes"); and, for a wall
//     clock that stands still, once an interval and a minute of monotonic
//     time have passed since the last checkpoint;
//   - at the field-off edge + 5 s (CRITICAL_ZONE_MS), if the field is still off;
//   - at every charging-stage transition;
//   - on stop.
// Call poll() regularly (e.g. each telemetry sample the store thread sees);
// a non-None answer means "checkpoint now", and the policy counts it as done.
#include <cstdint>
#include <string_view>

#include "core/modes.h"
#include "core/time.h"

namespace xr {

enum class CheckpointReason { None, Start, Interval, FieldOff, Stage, Stop };
std::string_view toString(CheckpointReason r);  // "interval", "field_off", ...

class CheckpointPolicy {
 public:
  explicit CheckpointPolicy(std::int64_t intervalS);
  // now: monotonic time; wallMs: the store's wall clock (UTC ms).
  CheckpointReason poll(TimeNs now, std::int64_t wallMs, bool fieldEnable, ChargeStage stage, bool stopping);

 private:
  std::int64_t intervalMs_;    // [store] checkpoint_interval_s, in ms
  std::int64_t wallSlot_ = 0;  // floor(wallMs / interval) at the last poll
  bool started_ = false;
  bool stopped_ = false;
  TimeNs last_ = 0;
  bool lastField_ = false;
  ChargeStage lastStage_ = ChargeStage::BULK;
  TimeNs fieldOffAt_ = -1;  // pending field-off checkpoint, -1 = none
};

}  // namespace xr
