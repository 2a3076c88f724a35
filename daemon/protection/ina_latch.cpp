// InaLatch::update(): evaluated every tick the driver read the alert.
#include "protection/ina_latch.h"

#include "params/constants.h"
#include "params/derived.h"

namespace xr {

void InaLatch::update(const InaLatchInput& in, const Params& p, const ProtectionLog& log) noexcept {
  if (p.INADisconnected) {
    latched_ = false;
    return;
  }
  // The alert is looked at on every tick the driver read DIAG_ALRT (the
  // chip's alert does not latch, so a 50 ms pulse polled every 250 ms was
  // missed 8 times in 10); the release checks keep the specification's
  // cadence (docs/deviations.md).
  const TimeNs now = log.now();
  if (!latched_) {
    if (!in.busOvervoltage) return;
    latched_ = true;
    latchedAt_ = now;
    nextCheck_ = now + fromMs(k::INA_LATCH_RELEASE_CHECK_MS);
    log.noteTrip(Reason::REASON_INA_OVERVOLTAGE);
    log.push(EventCode::InaLatchSet, EventLevel::Critical, Reason::REASON_INA_OVERVOLTAGE, in.IBV,
             voltageHardwareLimit(p));
  } else if (now >= nextCheck_) {
    if (!in.busOvervoltage) {
      latched_ = false;
      clearedAt_ = now;
      log.push(EventCode::InaLatchCleared, EventLevel::Warning, Reason::REASON_INA_OVERVOLTAGE, in.IBV,
               toSec(now - latchedAt_));
    } else {
      nextCheck_ = now + fromMs(k::INA_LATCH_RECHECK_MS);
    }
  }
}

bool InaLatch::suppressesDisagreement(TimeNs now) const noexcept {
  return latched_ || (clearedAt_ >= 0 && now - clearedAt_ < fromMs(k::INA_OV_DISAGREE_SUPPRESS_MS));
}

}  // namespace xr
