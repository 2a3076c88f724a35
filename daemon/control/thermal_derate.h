#pragma once
// T0: the temperature PID (docs/control.md "Temperature PID (T0)",
// docs/protections.md "Protections"). REVERSE action on the
// predictive projectedTempF; output thermalPenaltyAmps, slew-limited.
// This project's (docs/deviations.md "Thermal loop"): it regulates at
// TemperatureLimitF - TempRegulationMarginF, on max(projected, present), with
// a filter whose smoothing is per second (not per sample) and a slope that
// ignores physically impossible jumps.
#include <array>

#include "control/pid.h"
#include "core/time.h"
#include "params/constants.h"
#include "params/params.h"

namespace xr {

struct ThermalInputs {
  TimeNs now = 0;
  double dtSec = 0.0;
  double TempToUse = 0.0;  // degF from TempSource
  bool tempFresh = false;  // a new sample this tick
  bool tempValid = false;  // not stale, finite, within [-50, 400] degF
  // Implied-penalty anti-windup: what the non-thermal constraints already take
  // off I_cap (I_cap - the lowest non-thermal ceiling), amps.
  double impliedPenalty = 0.0;
};

class ThermalDerate {
 public:
  ThermalDerate();
  // Once per control tick. Returns thermalPenaltyAmps.
  // Real-time thread, every tick: neither allocates nor blocks (docs/architecture.md "Threads").
  double update(const ThermalInputs& in, const Params& p) noexcept;
  void reset() noexcept;

  double tempFiltered() const noexcept { return tempFiltered_; }
  double projectedTempF() const noexcept { return projectedTempF_; }
  double thermalSlopeFPerSec() const noexcept { return thermalSlopeFPerSec_; }
  double thermalPenaltyAmps() const noexcept { return thermalPenaltyAmps_; }
  double penaltyTarget() const noexcept { return tempPID_.output; }  // thermalPenaltyAmps_d
  double integrator() const noexcept { return tempPID_.iTerm(); }
  bool holding() const noexcept { return holding_; }

 private:
  Pid tempPID_;          // REVERSE-acting on the projected temperature: the penalty
  bool primed_ = false;  // the filter has its first sample
  // The filtered and projected temperature and its slope.
  double tempFiltered_ = 0.0, projectedTempF_ = 0.0, thermalSlopeFPerSec_ = 0.0;
  double thermalPenaltyAmps_ = 0.0;                                // the penalty, slew-limited
  TimeNs lastComputeNs_ = 0;                                       // the last PID compute (its own cadence)
  bool haveCompute_ = false;                                       // a compute has run
  std::array<double, k::THERMAL_SLOPE_BUF> thermalSlopeBuffer_{};  // recent temperatures (the slope)
  std::array<TimeNs, k::THERMAL_SLOPE_BUF> slopeStamps_{};         // ... and their times
  int slopeCount_ = 0, slopeHead_ = 0;                             // the ring's fill and head
  TimeNs lastSampleNs_ = 0;  // the last temperature sample taken into tempFiltered
  bool holding_ = false;     // the penalty holds on stale input
};

}  // namespace xr
