#pragma once
// CurrentChecks: hard overcurrent (MeasuredAmps > HardOCTripAmps for
// HardOCDebounceMs) and current data stale (docs/protections.md): no fresh
// CH1 sample for CurrentStaleMs, or no fresh INA228 sample for
// CurrentStaleMs in fast mode / CurrentStaleMs + 2 slow periods in slow mode
// (field off, ~1.05 s conversions) and for one slow period after switching
// to fast.
#include "core/inputs.h"
#include "core/time.h"
#include "params/params.h"
#include "protection/protection_log.h"

namespace xr {

struct CurrentChecksInput {
  double MeasuredAmps = kNoValue;  // zero-corrected alternator current
  TimeNs ch1Stamp = 0;             // the last CH1 sample, 0 = none yet
  TimeNs inaStamp = 0;             // the last INA228 sample (IBV or Bcur), 0 = none yet
  bool inaFastMode = false;        // the INA228 converts in fast mode
  TimeNs boot = 0;                 // the first tick (a sensor never read counts from it)
};

class CurrentChecks {
 public:
  void update(const CurrentChecksInput& in, const Params& p, const ProtectionLog& log) noexcept;
  bool hardOvercurrent() const noexcept { return hardOc_; }
  bool stale() const noexcept { return stale_; }

 private:
  SustainTimer overT_;        // over the trip for the debounce
  EventEdge evHardOc_;        // hard overcurrent trip/clear
  EventEdge evStale_;         // stale trip/clear
  bool inaFast_ = false;      // fast mode on the last update (edge detection)
  TimeNs inaFastSince_ = -1;  // when the INA228 last entered fast mode
  bool hardOc_ = false;       // hard overcurrent
  bool stale_ = false;        // current data stale
};

}  // namespace xr
