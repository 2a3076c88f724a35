#pragma once
// BankMismatchCheck: the bank size check (docs/deviations.md "Bank size
// check"). Every live voltage sensor (IBV unless INADisconnected, BatteryV)
// reads a bank size other than BulkVoltage's (the one 18/36 V rule,
// params/derived.h) for kHoldMs: every voltage threshold is wrong, so the
// field is cut in every mode. A dead sensor (< SENSOR_DEAD_V) is left to the
// disagreement and implausibility detectors.
#include <cstdint>

#include "core/inputs.h"
#include "core/time.h"
#include "params/params.h"
#include "protection/protection_log.h"

namespace xr {

struct BankMismatchInput {
  double IBV = kNoValue;
  double BatteryV = kNoValue;
};

class BankMismatchCheck {
 public:
  // How long every voltage sensor must read another bank size before the
  // field is cut: long enough to ride through a 24 V starter's cranking dip,
  // short enough that a 24 V target on a 12 V bank cannot lift it far (the
  // governor's slew needs seconds).
  static constexpr std::int64_t kHoldMs = 5000;

  void update(const BankMismatchInput& in, const Params& p, const ProtectionLog& log) noexcept;
  bool mismatch() const noexcept { return mismatch_; }

 private:
  SustainTimer held_;      // every live sensor reads another bank size
  EventEdge ev_;           // trip/clear
  bool mismatch_ = false;  // held for kHoldMs
};

}  // namespace xr
