#pragma once
// InaLatch: the INA228 hardware ALERT's software latch (docs/protections.md
// "INA228 Hardware ALERT — Software latch"). The chip's alert has already
// pulled GPIO4 LOW in hardware; the latch keeps the field off in software
// until a release check finds the bus back under the limit: the first 3 s
// after latching, then every 10 s.
#include "core/inputs.h"
#include "core/time.h"
#include "params/params.h"
#include "protection/protection_log.h"

namespace xr {

struct InaLatchInput {
  bool busOvervoltage = false;  // the driver read DIAG_ALRT's bus-overvoltage bit this tick
  double IBV = kNoValue;        // for the event's value
};

class InaLatch {
 public:
  void update(const InaLatchInput& in, const Params& p, const ProtectionLog& log) noexcept;
  bool latched() const noexcept { return latched_; }
  // The disagreement detectors look away while latched and for
  // INA_OV_DISAGREE_SUPPRESS_MS after the release (the INA228 reading is the
  // one that was over the limit).
  bool suppressesDisagreement(TimeNs now) const noexcept;

 private:
  bool latched_ = false;   // the software latch (field off while set)
  TimeNs latchedAt_ = 0;   // when it latched (the release event's duration)
  TimeNs nextCheck_ = 0;   // the next release check
  TimeNs clearedAt_ = -1;  // the last release, -1 = never
};

}  // namespace xr
