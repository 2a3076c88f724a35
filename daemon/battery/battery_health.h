#pragma once
// BatteryHealth: the bank's measured capacity and internal resistance
// (docs/batteries.md "Measured capacity", "Internal resistance"). It owns
// the two estimators and the BMS's SoC of this interval, a point of known
// SoC for the capacity. Pure: no clock, no I/O.
#include "battery/capacity_tracker.h"
#include "battery/resistance_estimator.h"
#include "core/events.h"
#include "core/inputs.h"
#include "core/time.h"

namespace xr {

// What one tick hands the health figures.
struct HealthInput {
  double dt_s = 0.0;
  double amps = kNoValue;       // battery current (+ = charging), NaN when not measured
  double volts = kNoValue;      // battery voltage, NaN when not measured
  double tempC = kNoValue;      // battery temperature while it counts, else NaN (25 degC assumed)
  double bmsSocPct = kNoValue;  // a fresh SoC from a BMS, else NaN
  double capacityAh = 0.0;      // BatteryCapacity_Ah
};

class BatteryHealth {
 public:
  // Every tick. True when the resistance took a new sample.
  bool update(const HealthInput& in) noexcept;
  // Each SoC interval: the corrected Ah the count added.
  void addAh(double correctedAh, double elapsed_s) noexcept { capacity_.addAh(correctedAh, elapsed_s); }
  // A point of known SoC (full charge, rested voltage, the BMS's SoC). Emits
  // CapacityMeasured and returns true when it completed a measured swing.
  bool knownSoc(TimeNs now, double socPct, bool full, double capacityAh, EventBatch& ev) noexcept;
  // The BMS's SoC of the last tick (NaN: none fresh).
  double bmsSocPct() const noexcept { return bmsSocPct_; }

  const CapacityTracker& capacity() const noexcept { return capacity_; }
  const ResistanceEstimator& resistance() const noexcept { return resistance_; }
  void toLedger(BatteryLedger& l) const noexcept {
    l.capacity = capacity_.ledger();
    l.resistance = resistance_.ledger();
  }
  void restore(const BatteryLedger& l) noexcept {
    capacity_.restore(l.capacity);
    resistance_.restore(l.resistance);
  }

 private:
  CapacityTracker capacity_;        // capacity between points of known SoC
  ResistanceEstimator resistance_;  // DC resistance from the current steps
  double bmsSocPct_ = kNoValue;     // a fresh SoC from a BMS, for the next SoC interval
};

}  // namespace xr
