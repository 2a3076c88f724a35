#pragma once
// ResistanceEstimator: the bank's DC internal resistance from the current
// steps that happen anyway (docs/batteries.md "Internal resistance"). It
// keeps one-second means of the battery's voltage and current; a step is a
// current that held for kBeforeS, changed by at least max(kMinStepA, C/100),
// then held again for kAfterS. R = dV/dI between the kBeforeS before the
// step and the last kMeasureS of the hold: late enough that the fast
// polarisation (tens of seconds) is in, as a load or a field ramp sees it.
// Only steps where the bank is not being charged count: on charge the
// end-of-charge overpotential is not a resistance. Each sample is corrected
// to 25 degC; the figure is the median of the last kResistanceSamples.
// Pure: no clock, no I/O, no allocation.
#include <array>

#include "battery/ledger.h"

namespace xr {

namespace resistance_k {
inline constexpr int kBeforeS = 10;   // steady seconds before the step
inline constexpr int kAfterS = 120;   // steady seconds after it (the last kMeasureS are measured)
inline constexpr int kMeasureS = 30;  // 90..120 s after the step
inline constexpr int kSkipS = 2;      // the step's own seconds, mixed
inline constexpr int kWindowS = kBeforeS + kAfterS;
// The smallest step: a fridge compressor's 3-5 A is the step an ordinary day
// offers most (two or more an hour), so the floor is under it. C/100 moves a
// 12 V bank's voltage by 4 mV (LiFePO4, ~0.4 ohm-Ah) to 7 mV (AGM, ~0.7
// ohm-Ah as read here), twenty times the INA228's 195 uV step and several
// times the ~1 mV a discharging bank drifts in the two minutes; the median
// of 16 keeps the odd step spoiled by drift out (docs/batteries.md
// "Internal resistance").
inline constexpr double kMinStepA = 2.0;
inline constexpr double kMinStepC = 1.0 / 100.0;  // of the capacity, per hour
// "Steady": every second within this of the window's mean.
inline constexpr double kSteadyA = 1.0, kSteadyShare = 0.03;
inline constexpr double kMaxChargeA = 0.5;  // "not being charged"
// Nor charged for this long before the window: after a charge the bank's
// voltage sinks for hours as the charge's polarisation relaxes, and that
// drift is not the step's (docs/batteries.md "Internal resistance").
inline constexpr double kAfterChargeS = 1800.0;
inline constexpr int kMinSamples = 5;  // before a figure is shown
// Plausible bank resistance, 25 degC (a 2000 Ah LiFePO4 bank to a 12 V toy).
inline constexpr double kMinMohm = 0.05, kMaxMohm = 500.0;
// Temperature law of the resistance: Arrhenius, B = 1697 K (docs/sources.md P3.4:
// R(-20 degC) = 2.75 x R(25 degC)).
inline constexpr double kArrheniusB = 1697.0;
}  // namespace resistance_k

class ResistanceEstimator {
 public:
  // Every tick: dt since the last, the battery current (+ = charging) and
  // voltage (NaN when not measured), the battery temperature (NaN: 25 degC
  // assumed), and the configured capacity (for the smallest step).
  // Returns true when a new sample was taken.
  bool update(double dt_s, double amps, double volts, double tempC, double capacityAh) noexcept;
  // Median and spread (standard deviation) of the samples held, mOhm; NaN below kMinSamples.
  double medianMohm() const noexcept;
  double spreadMohm() const noexcept;
  int samples() const noexcept { return static_cast<int>(l_.count); }
  // The resistance at `tempC` (for the rested-voltage correction), ohm; NaN when unknown.
  double ohmsAt(double tempC) const noexcept;
  // A factor R(T) / R(25 degC).
  static double temperatureFactor(double tempC) noexcept;

  const ResistanceLedger& ledger() const noexcept { return l_; }
  void restore(const ResistanceLedger& l) noexcept;

 private:
  bool closeSecond(double tempC, double capacityAh) noexcept;
  bool detectStep(double& rMohm, double capacityAh) const noexcept;
  void push(double rMohm) noexcept;
  ResistanceLedger l_;
  // One-second means, oldest first at ring_[head_].
  std::array<double, resistance_k::kWindowS> secA_{}, secV_{};
  int head_ = 0, filled_ = 0;
  double accA_ = 0.0, accV_ = 0.0, accT_ = 0.0;
  bool gap_ = false;            // a second without a measurement breaks the window
  double sinceCharge_s_ = 0.0;  // seconds since the bank was last charged
};

}  // namespace xr
