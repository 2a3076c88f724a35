#pragma once
// OcvReanchor: points of known state of charge from a lead-acid bank's
// rested voltage (docs/batteries.md "State of charge at first start",
// "Measured capacity"). Two detectors, each with its own rest timer:
//  - the first-start estimate: 30 s of rest while the SoC is unknown gives a
//    figure to count from, shown as an estimate;
//  - the rested-voltage point: 4 h of rest gives a SoC good to about 1 %,
//    handed to the next SoC interval (the measured capacity's point, and the
//    count's anchor until a full charge has set it).
// LiFePO4's voltage is flat from 20 % to 90 % (docs/sources.md §3.1), so a
// LiFePO4 or custom bank gives no point. Pure: no clock, no I/O.
#include "core/inputs.h"
#include "params/params.h"

namespace xr {

class ResistanceEstimator;

// What one tick hands the rest detectors.
struct RestInput {
  double dt_s = 0.0;
  double amps = 0.0;        // battery current, NaN when not measured
  double volts = 0.0;       // battery voltage, NaN when not measured
  double altAmps = 0.0;     // alternator current (NaN: unknown, counted as off)
  double tempC = 0.0;       // battery temperature, NaN when none
  int nominalVoltage = 12;  // the bank class's 12 / 24 / 48 V
};

class OcvReanchor {
 public:
  // Every tick while the SoC is unknown: the SoC (%) once the bank has
  // rested 30 s, else NaN. Restarts its timer on any tick not at rest.
  double firstStartEstimate(const RestInput& in, bool socUnknown, const Params& p) noexcept;
  // Every tick: follows a rest towards its 4 h point; the open-circuit
  // voltage is the terminal voltage less what the small rest current drops
  // across the bank's resistance (when known).
  void trackRestedPoint(const RestInput& in, const Params& p, const ResistanceEstimator& r) noexcept;
  // The rested-voltage point not yet used (NaN: none); taking it clears it.
  double takeRestedPoint() noexcept;

  // A lead-acid bank at rest: little current, a voltage, the alternator off.
  static bool leadAcidAtRest(double amps, double volts, double altAmps, const Params& p) noexcept;
  // The SoC a rested voltage says (per 12 V: BatteryCells, else the class's 6 per 12 V).
  static double socFromRestVolts(double volts, const Params& p, int nominalVoltage) noexcept;

 private:
  double startRest_s_ = 0.0;         // first-start estimate: seconds at rest so far
  double startVolt_s_ = 0.0;         // its voltage integral (V s)
  double rest_s_ = 0.0;              // rested point: seconds at rest so far
  double restV_s_ = 0.0;             // voltage integral over the last hour of it (V s)
  double restA_s_ = 0.0;             // current integral over the same hour (A s)
  double restAvg_s_ = 0.0;           // seconds in those integrals
  bool restTaken_ = false;           // this rest gave its point
  double pendingSocPct_ = kNoValue;  // a point for the next SoC interval (NaN: none)
};

}  // namespace xr
