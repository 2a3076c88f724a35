// PendingEvents: command events held for the next step.
#include "control/pending_events.h"

namespace xr {

bool PendingEvents::queue(const Event& e) noexcept {
  if (count_ >= events_.size()) return false;
  events_[count_++] = e;
  return true;
}

void PendingEvents::drainInto(EventBatch& ev) noexcept {
  for (std::size_t i = 0; i < count_; ++i) ev.push(events_[i]);
  count_ = 0;
}

}  // namespace xr
