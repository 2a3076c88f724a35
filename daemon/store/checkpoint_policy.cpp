#include "store/checkpoint_policy.h"

#include "params/constants.h"
#include "store/floor_div.h"

namespace xr {

std::string_view toString(CheckpointReason r) {
  switch (r) {
    case CheckpointReason::None:
      return "none";
    case CheckpointReason::Start:
      return "start";
    case CheckpointReason::Interval:
      return "interval";
    case CheckpointReason::FieldOff:
      return "field_off";
    case CheckpointReason::Stage:
      return "stage";
    case CheckpointReason::Stop:
      return "stop";
  }
  return "none";
}

CheckpointPolicy::CheckpointPolicy(std::int64_t intervalS)
    : intervalMs_(1000 * (intervalS > 0 ? intervalS : 300)) {}

CheckpointReason CheckpointPolicy::poll(TimeNs now, std::int64_t wallMs, bool fieldEnable, ChargeStage stage,
                                        bool stopping) {
  if (stopped_) return CheckpointReason::None;
  CheckpointReason r = CheckpointReason::None;
  const std::int64_t slot = store::floorDiv(wallMs, intervalMs_);
  if (!started_) {
    // First sight: remember the state; the timer starts now. The runtime
    // has just restored the ledger, so there is nothing new to save.
    started_ = true;
    last_ = now;
    lastField_ = fieldEnable;
    lastStage_ = stage;
    wallSlot_ = slot;
  }
  if (lastField_ && !fieldEnable) fieldOffAt_ = now + fromMs(k::CRITICAL_ZONE_MS);
  if (fieldEnable) fieldOffAt_ = -1;  // back on: the interval covers it
  const bool stageChanged = stage != lastStage_;
  const bool newWallInterval = slot != wallSlot_;
  wallSlot_ = slot;
  lastField_ = fieldEnable;
  lastStage_ = stage;

  if (stopping) {
    stopped_ = true;
    r = CheckpointReason::Stop;
  } else if (stageChanged) {
    r = CheckpointReason::Stage;
  } else if (fieldOffAt_ >= 0 && now >= fieldOffAt_) {
    r = CheckpointReason::FieldOff;
  } else if (newWallInterval || now - last_ >= fromMs(intervalMs_) + fromSec(60)) {
    r = CheckpointReason::Interval;
  }
  if (r != CheckpointReason::None) {
    last_ = now;
    if (r == CheckpointReason::FieldOff || r == CheckpointReason::Stop) fieldOffAt_ = -1;
  }
  return r;
}

}  // namespace xr
