#pragma once
// ShuntGainCorrector: the battery shunt's gain, corrected at each detected
// full charge from how far the count since the last known point missed the
// configured capacity (docs/batteries.md "Auto shunt-gain correction"). It
// owns the factor and its rate limit. Pure: no clock, no I/O.
#include <cstdint>

#include "core/events.h"
#include "core/time.h"

namespace xr {

namespace battery_k {
// At most one correction per 24 h: full-charge detection repeats every
// SOCUpdateInterval while it holds, and a calibration should average over a
// whole cycle, not react to the same full charge twice.
inline constexpr std::int64_t MIN_GAIN_CORRECTION_INTERVAL_MS = 24LL * 3600 * 1000;
// |expected - calculated| / expected above this is a sensor or wiring fault,
// not a calibration error: do nothing.
inline constexpr double MAX_REASONABLE_ERROR = 0.20;
// Per-event rate limit: the factor moves at most 2 % per full charge.
inline constexpr double MAX_GAIN_ADJUSTMENT_PER_CYCLE = 0.02;
// Absolute bounds: a shunt is never off by more than 10 % after manufacture.
inline constexpr double MIN_DYNAMIC_GAIN_FACTOR = 0.90;
inline constexpr double MAX_DYNAMIC_GAIN_FACTOR = 1.10;
// Plausibility floor of both capacities (Ah).
inline constexpr double MIN_PLAUSIBLE_CAPACITY_AH = 10.0;
}  // namespace battery_k

// Why an auto-gain correction was skipped (detail code of events/tests).
enum class GainGuard {
  Applied = 0,
  FeatureOff,
  TooSoon,      // MIN_GAIN_CORRECTION_INTERVAL
  NoReference,  // no full charge / setSoc since boot: count is not a measurement
  ImplausibleCapacity,
  ErrorTooLarge,  // MAX_REASONABLE_ERROR
};

// What a detected full charge hands the corrector.
struct GainCorrectionInput {
  TimeNs now = 0;
  bool enabled = false;               // AutoShuntGainCorrection
  bool referenceValid = false;        // a known point (full charge, set SoC) this session
  double countSinceReference_Ah = 0;  // the count at full, unclamped, since that point
  double expectedCapacity_Ah = 0;     // BatteryCapacity_Ah
};

class ShuntGainCorrector {
 public:
  // At a detected full charge, before the count is reset to the capacity.
  // Emits ShuntGainCorrected when applied or when the error is too large.
  void atFullCharge(const GainCorrectionInput& in, EventBatch& ev) noexcept;
  double factor() const noexcept { return factor_; }
  double corrected(double rawAmps) const noexcept { return rawAmps * factor_; }
  GainGuard lastGuard() const noexcept { return lastGuard_; }
  void reset() noexcept { factor_ = 1.0; }
  // A saved factor; NaN restores 1, anything else is clamped to its bounds.
  void restore(double factor) noexcept;

 private:
  double factor_ = 1.0;                          // DynamicShuntGainFactor: multiplies the shunt current
  bool haveCorrection_ = false;                  // lastCorrection_ holds a correction of this session
  TimeNs lastCorrection_ = 0;                    // the 24 h rate limit runs from here
  GainGuard lastGuard_ = GainGuard::FeatureOff;  // the last outcome (tests, diagnostics)
};

}  // namespace xr
