#pragma once
// SocCounter: the state of charge as counted amp-hours (docs/batteries.md
// "State of charge"): the interval's current integral committed with charge
// efficiency in and Peukert out, the source the figure is shown with, the
// full-charge detector that resets it to the capacity, the count since the
// last known point (for the shunt-gain correction) and the time-to-full /
// time-to-empty prediction from it. Pure: no clock, no I/O.
#include "battery/battery_telemetry.h"
#include "battery/ledger.h"
#include "params/params.h"

namespace xr {

namespace battery_k {
// The coulomb accumulator is committed in 0.01 Ah steps, remainder kept.
inline constexpr double COULOMB_COMMIT_AH = 0.01;
}  // namespace battery_k

// SoC assumed before anything was restored or measured (see the constructor).
inline constexpr double kUnknownSocPercent = 100.0;

// What the full-charge detector sees at each SoC interval.
struct FullChargeInput {
  double elapsed_s = 0.0;  // since the last interval
  bool live = false;       // current and voltage both measured: a dead sensor reads 0 A
  double amps = 0.0;       // battery current (+ = charging)
  double volts = 0.0;      // battery voltage
};

class SocCounter {
 public:
  // A fresh count does not know the SoC: it guesses full (see the .cpp).
  explicit SocCounter(double capacityAh) noexcept;

  // Every tick with a measured current: amps held over dt.
  void integrate(double amps, double dt_s) noexcept { intervalAh_ += amps * dt_s / 3600.0; }
  // Each SoC interval: commits the interval's Ah (efficiency, Peukert, 0.01
  // Ah steps, clamped to 0..capacity) and returns the corrected Ah it added.
  double commit(double elapsed_s, const Params& p) noexcept;
  // Each SoC interval: true when the bank has held the tail current at the
  // charged voltage for ChargedDetectionTime (the caller declares it full).
  bool fullChargeDue(const FullChargeInput& in, const Params& p) noexcept;
  // A full charge declared (by the detector or the charging stage's tail):
  // count = capacity, source Counted, a new reference point.
  void markFull(double capacityAh) noexcept;
  // A SoC known from elsewhere (a value set, a rested voltage).
  void setPercent(double pct, double capacityAh, SocSource source) noexcept;
  // A value set by the operator: also a reference point for the gain.
  void setByOperator(double pct, double capacityAh) noexcept;
  void clampTo(double capacityAh) noexcept;
  // Time to full / to empty at `amps` (PREDICTION_NA when not applicable).
  void predict(double amps, double capacityAh) noexcept;

  double percent(double capacityAh) const noexcept {
    if (!(capacityAh > 0.0)) return 0.0;
    return count_Ah_ / capacityAh * 100.0;
  }
  double countAh() const noexcept { return count_Ah_; }
  SocSource source() const noexcept { return source_; }
  bool fullDetected() const noexcept { return fullDetected_; }
  bool referenceValid() const noexcept { return referenceValid_; }
  double sinceReferenceAh() const noexcept { return sinceReference_Ah_; }
  double timeToFullMin() const noexcept { return timeToFullMin_; }
  double timeToEmptyMin() const noexcept { return timeToEmptyMin_; }

  void toLedger(BatteryLedger& l) const noexcept;
  // Restores count, remainder and source; a damaged count restarts unknown.
  void restore(const BatteryLedger& l, double capacityAh) noexcept;

  // (PeukertRatedCurrent_A / I)^(n-1) clamped to 0.5..2.0, or 1 at or below C/100.
  static double peukertFactor(double dischargeCurrent_A, double capacity_Ah, double ratedCurrent_A,
                              double exponent) noexcept;

 private:
  double count_Ah_;                        // CoulombCount_Ah: SoC = count / capacity
  double remainder_Ah_ = 0.0;              // below one 0.01 Ah step, not yet committed
  SocSource source_ = SocSource::Unknown;  // what the count rests on (shown with the figure)
  double intervalAh_ = 0.0;                // signed Ah this interval, before efficiency/Peukert
  bool referenceValid_ = false;            // a full charge or a set SoC happened this session
  double sinceReference_Ah_ = 0.0;         // the count since that point, without the 0..cap clamp
  double fullTimer_s_ = 0.0;               // time the full-charge condition has held
  bool fullDetected_ = false;              // declared full and still holding
  double timeToFullMin_ = -999.0;          // prediction at the present charge current (min)
  double timeToEmptyMin_ = -999.0;         // prediction at the present discharge current (min)
};

}  // namespace xr
