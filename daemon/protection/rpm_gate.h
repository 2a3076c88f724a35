#pragma once
// RpmGate: RPM < MinRPMForField cuts the field (docs/protections.md "RPM
// gate"); an unknown RPM counts as below. A resting field (control's
// full-bank rest) quiets a stator tach: during the rest and
// RPM_REST_GRACE_MS after, an RPM that was fine when the rest began still
// counts (docs/deviations.md "Full bank at light load").
#include "core/inputs.h"
#include "core/time.h"
#include "params/params.h"
#include "protection/protection_log.h"

namespace xr {

struct RpmGateInput {
  double rpm = kNoValue;      // engine speed, NaN = unknown
  bool fieldResting = false;  // control's field rest of the last tick
};

class RpmGate {
 public:
  void update(const RpmGateInput& in, const Params& p, const ProtectionLog& log) noexcept;
  bool belowMin() const noexcept { return below_; }

 private:
  bool below_ = false;          // the gate holds the field off
  bool okAtRestStart_ = false;  // the RPM was fine when the current rest began
  bool wasResting_ = false;     // the field rested on the last update (edge detection)
  TimeNs restEndedAt_ = -1;     // the last rest's end, -1 = none yet
  bool everRead_ = false;       // an engine speed was read since start
  EventEdge ev_;                // trip/clear
};

}  // namespace xr
