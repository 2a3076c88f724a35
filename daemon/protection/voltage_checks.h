#pragma once
// VoltageChecks: the detectors of the two voltage sensors
// (docs/protections.md "Protections"): the alternator hard shutdown
// (IBV > AlternatorHardShutdownV), the disagreement between the INA228 (IBV)
// and the battery sense (BatteryV) at its warning and critical levels, and
// the implausibility of both at once.
#include "core/inputs.h"
#include "core/time.h"
#include "params/params.h"
#include "protection/protection_log.h"

namespace xr {

struct VoltageChecksInput {
  double IBV = kNoValue;       // INA228 bus voltage
  double BatteryV = kNoValue;  // battery sense
  bool notReadYet = false;     // a sensor has not delivered its first sample within the boot grace
  bool inaLatched = false;     // the INA228 latch is set this tick (one log line for both)
  bool suppressed = false;     // InaLatch::suppressesDisagreement()
};

class VoltageChecks {
 public:
  void update(const VoltageChecksInput& in, const Params& p, const ProtectionLog& log) noexcept;
  bool altHardShutdown() const noexcept { return altHs_; }
  bool disagreeWarning() const noexcept { return disW_; }
  bool disagreeCritical() const noexcept { return disC_; }
  bool implausible() const noexcept { return impl_; }

 private:
  void updateDisagreement(const VoltageChecksInput& in, const Params& p, const ProtectionLog& log) noexcept;

  SustainTimer warnT_, critT_;  // disagreement held for its timeout (warning, critical)
  EventEdge evAltHs_;           // hard shutdown trip/clear
  EventEdge evDisW_, evDisC_;   // disagreement trip/clear (warning, critical)
  EventEdge evImpl_;            // implausibility trip/clear
  bool altHs_ = false;          // IBV > AlternatorHardShutdownV this tick
  bool disW_ = false;           // disagreement warning
  bool disC_ = false;           // disagreement critical (or a dead sensor)
  bool impl_ = false;           // both sensors outside the plausible range
};

}  // namespace xr
