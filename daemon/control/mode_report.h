#pragma once
// ModeReport: what the regulator last told about its field (docs/operations.md
// "Events"): the mode and its reason, and the field enable, so that a change
// is one ModeChanged / FieldOn / FieldOff event and not one per tick.
#include "core/events.h"
#include "core/modes.h"
#include "protection/mode_selection.h"

namespace xr {

class ModeReport {
 public:
  // True when the mode differs from the last tick's (always on the first tick).
  bool changes(const ModeDecision& d) const noexcept { return first_ || d.mode != mode_; }
  // After the mode's entry: the ModeChanged event when it changed. The first
  // tick before the first engine-speed reading stays quiet: the field waits
  // off, but no engine stopped (docs/protections.md "First readings").
  void noteMode(const ModeDecision& d, bool rpmUnread, TimeNs now, EventBatch& ev) noexcept;
  // The field enable of this tick: FieldOn / FieldOff on an edge. Returns
  // true on the rising edge.
  bool noteField(bool field, const ModeDecision& d, TimeNs now, EventBatch& ev) noexcept;

  bool firstTick() const noexcept { return first_; }
  FieldControlMode mode() const noexcept { return mode_; }
  Reason reason() const noexcept { return reason_; }
  bool field() const noexcept { return field_; }

 private:
  bool first_ = true;                                             // no tick reported yet
  FieldControlMode mode_ = FieldControlMode::MODE_DISABLED_RAMP;  // the last tick's mode
  Reason reason_ = Reason::NONE;                                  // ... and its reason
  bool field_ = false;                                            // the last tick's field enable
};

}  // namespace xr
