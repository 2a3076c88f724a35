#pragma once
// FieldRest (docs/deviations.md "Full bank at light load"): the RPM duty
// floor (rpmMinDutyTable, for the tach signal) can push more current than a
// full bank at light load takes: the voltage then climbs past the target
// into the over-voltage protections. When the voltage loop asks for less
// than the floor, or for no current at all, and the bank still sits above
// its target for FieldRestDelayMs, the field rests (enable LOW, duty 0)
// until the voltage falls back under the target.
#include "core/inputs.h"
#include "params/params.h"

namespace xr {

// What the rest reads: the loops' state of this tick.
struct RestInputs {
  TimeNs now = 0;
  bool tuningActive = false;  // TuningMode, CVTuningMode or a SystemID run owns the field
  bool voltageControlActive = false;
  double ChargingVoltageTarget = 0.0;
  double IBV = kNoValue;
  double rpmMinDuty = 0.0;
  double dutyRequest = 0.0;
  double setpointCommand = 0.0;
};

class FieldRest {
 public:
  // After the inner loop: true when a rest starts now (the condition held
  // for FieldRestDelayMs).
  bool startDue(const RestInputs& in, const Params& p) noexcept;
  // On a fresh CH1 while resting: true when the rest ends now.
  bool endDue(const RestInputs& in, const Params& p) noexcept;
  // Leaving AUTO ends a rest and its arming.
  void leave() noexcept {
    resting_ = false;
    armedAt_ = -1;
  }
  bool resting() const noexcept { return resting_; }

 private:
  // The voltage loop "asks for no current" at or under this command.
  static constexpr double kRestNoCurrentA = 0.05;

  bool resting_ = false;  // the field rests (enable LOW) in AUTO
  TimeNs armedAt_ = -1;   // the rest condition holds since (-1: not holding)
};

}  // namespace xr
