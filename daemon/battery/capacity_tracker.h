#pragma once
// CapacityTracker: the bank's real capacity, measured between two points of
// known state of charge (docs/batteries.md "Measured capacity"). Between the
// points it adds up the amp-hours the SoC counts (charge efficiency in,
// Peukert out); at the second point, capacity = |Ah| / |SoC swing|. Only a
// swing of at least kMinSwingPct is measured, and a figure is reported only
// once kMinCycles swings agree with it. Pure: no clock, no I/O.
#include "battery/ledger.h"

namespace xr {

namespace capacity_k {
// A swing smaller than this is dominated by the SoC points' own error (a
// rested voltage is good to a few %, a BMS's SoC to 1 %).
inline constexpr double kMinSwingPct = 30.0;
// Swings needed before a figure is shown: one can be one odd day.
inline constexpr int kMinCycles = 2;
// Each new swing weighs this much more than the ones before, so a bank
// that ages is followed within a few cycles.
inline constexpr double kFade = 0.7;
// A point this old is not joined to a new one: the count drifts with time
// (shunt offset, self-discharge), so the anchor moves to the new point.
inline constexpr double kMaxAnchorAge_s = 14.0 * 86400.0;
// A swing giving less than this share of the configured capacity, or more
// than the upper one, is a wiring or sensor fault, not a capacity: dropped.
inline constexpr double kMinShare = 0.3, kMaxShare = 2.0;
}  // namespace capacity_k

// What a point of known SoC did.
enum class CapacityPointResult { Anchored, Held, Measured, Rejected };

class CapacityTracker {
 public:
  // Counted amp-hours (+ into the bank) over `elapsed_s`, corrected as the SoC corrects them.
  void addAh(double correctedAh, double elapsed_s) noexcept;
  // A point where the true SoC is known (a full charge, a rested voltage, a
  // BMS's SoC). `full` marks a detected full charge: it always replaces a
  // nearby point, since current into a full bank is not stored.
  CapacityPointResult knownSoc(double socPct, bool full, double configuredAh) noexcept;
  // The measured capacity, NaN while fewer than kMinCycles swings were measured.
  double measuredAh() const noexcept;
  int cycles() const noexcept { return static_cast<int>(l_.Cycles); }
  // The last swing's figure (Ah) and size (%), for the event.
  double lastSampleAh() const noexcept { return lastSampleAh_; }
  double lastSwingPct() const noexcept { return lastSwingPct_; }

  const CapacityLedger& ledger() const noexcept { return l_; }
  // Restores the saved state; damaged values start the measurement afresh.
  void restore(const CapacityLedger& l) noexcept;

 private:
  void anchor(double socPct) noexcept;
  CapacityLedger l_;
  double lastSampleAh_ = 0.0, lastSwingPct_ = 0.0;
};

}  // namespace xr
