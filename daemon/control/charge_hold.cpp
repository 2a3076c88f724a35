// ChargeHoldDetector (see charge_hold.h).
#include "control/charge_hold.h"

#include <cmath>

namespace xr {

void ChargeHoldDetector::update(TimeNs now, double dt, const ChargeHoldSample& s, EventBatch& ev) noexcept {
  const bool holding = s.engineRunning && !s.bankFull && !s.ownerChoice && std::isfinite(s.batteryA) &&
                       s.batteryA < kNothingInA && s.cause != ChargeHold::NONE;
  if (holding) {
    heldS_ += dt;
    notHeldS_ = 0.0;
    cause_ = s.cause;
    if (!reported_ && heldS_ >= kHoldS) {
      reported_ = true;
      reportedCause_ = cause_;
      ev.push(makeEvent(now, EventLevel::Warning, EventCode::ChargingHeld, Reason::NONE, heldS_ / 60.0, 0.0,
                        static_cast<int>(cause_)));
    }
    return;
  }
  if (heldS_ <= 0.0) return;
  notHeldS_ += dt;
  if (notHeldS_ < kEndS) return;
  if (reported_)
    ev.push(makeEvent(now, EventLevel::Info, EventCode::ChargingHeld, Reason::NONE, heldS_ / 60.0, 0.0,
                      static_cast<int>(reportedCause_)));
  heldS_ = notHeldS_ = 0.0;
  reported_ = false;
  cause_ = reportedCause_ = ChargeHold::NONE;
}

}  // namespace xr
