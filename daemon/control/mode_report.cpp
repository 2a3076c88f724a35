// ModeReport: one event per change of the field's mode or enable.
#include "control/mode_report.h"

namespace xr {

void ModeReport::noteMode(const ModeDecision& d, bool rpmUnread, TimeNs now, EventBatch& ev) noexcept {
  if (changes(d) && !(first_ && rpmUnread))
    ev.push(makeEvent(now, isNormalMode(d.mode) ? EventLevel::Info : EventLevel::Warning,
                      EventCode::ModeChanged, d.reason, static_cast<double>(mode_), 0.0, 0, d.mode));
  first_ = false;
  mode_ = d.mode;
  reason_ = d.reason;
}

bool ModeReport::noteField(bool field, const ModeDecision& d, TimeNs now, EventBatch& ev) noexcept {
  const bool rising = field && !field_;
  if (rising)
    ev.push(makeEvent(now, EventLevel::Info, EventCode::FieldOn, Reason::NONE, 0.0, 0.0, 0, d.mode));
  else if (!field && field_)
    ev.push(makeEvent(now, EventLevel::Info, EventCode::FieldOff, d.reason, 0.0, 0.0, 0, d.mode));
  field_ = field;
  return rising;
}

}  // namespace xr
