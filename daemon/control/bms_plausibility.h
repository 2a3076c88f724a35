#pragma once
// BmsPlausibility: does what a BMS says fit the bank the regulator knows
// (docs/protections.md "BMS plausibility")? The BMS is obeyed either way
// (the charge never goes above what either side allows); a value that does
// not fit is told to the owner, once per episode, naming what does not fit
// and what to check:
//   CVL_CLASS            its CVL belongs to another bank class (a 14.2 V
//                        CVL on a 24 V bank: a BMS set up for 4 cells)
//   CELL_VOLTAGE         its cell readings are no lithium cell's, or do
//                        not fit the pack the regulator measures over its
//                        cells (6.5 V "cells" on an 8-cell bank at 26 V)
//   PACK_VOLTAGE         its pack voltage is far from the regulator's own
//                        (the voltage disagreement threshold of the class)
//   WARNING_CELLS_NORMAL a high-voltage warning holds charging while every
//                        cell it reports reads normal
// Cell readings that do not fit are not followed by the highest cell's
// ceiling (they would hold a bank the BMS does not measure); the CVL, CCL,
// charge-disable and warnings still are. Pure: time comes in, no heap.
#include <cstdint>
#include <string_view>

#include "core/bms_limits.h"
#include "core/charge_checks.h"
#include "core/events.h"
#include "params/params.h"

namespace xr {

// What the regulator knows of its bank: cells in series and the class.
struct BankShape {
  int cells = 4;
  int nominalV = 12;  // 12 / 24 / 48
};
BankShape bankShape(const Params& p) noexcept;

class BmsPlausibility {
 public:
  // A mismatch holds this long before it is one (a BMS starting up sends
  // its frames one by one), well inside the minute the owner is told in.
  static constexpr double kConfirmS = 10.0;
  // ...and everything fits this long before the episode is over.
  static constexpr double kClearS = 60.0;
  // Any lithium cell that is still a cell reads within these.
  static constexpr double kCellLowestV = 1.5, kCellHighestV = 4.5;
  // The pack over its cells may sit this far outside the BMS's lowest and
  // highest cell (cable drop at full current, the two meters' error).
  static constexpr double kCellFitV = 0.15;
  // A cell this far under BmsCellHighV (or 3.45 V with it off) is normal.
  static constexpr double kCellNormalMarginV = 0.1;

  // What does not fit now (no timing); NONE when all fits or nothing is known.
  static BmsMismatch check(const BmsLimits& b, double packV, const Params& p, double* a = nullptr,
                           double* bv = nullptr) noexcept;
  // The cell readings fit the bank (or there are none).
  static bool cellsFit(const BmsLimits& b, double packV, const Params& p) noexcept;

  // Once per tick while a BMS source is fresh; `stale` or no source ends
  // nothing by itself (the stale alarm speaks for a silent BMS).
  void update(const BmsLimits& b, TimeNs now, double packV, const Params& p, EventBatch& ev) noexcept;
  void reset() noexcept;

  BmsMismatch reported() const noexcept { return reported_; }  // NONE when no episode
  bool active() const noexcept { return reported_ != BmsMismatch::NONE; }

 private:
  BmsMismatch reported_ = BmsMismatch::NONE;  // the mismatch told
  TimeNs seenSince_ = -1;                     // a mismatch seen continuously since
  TimeNs fitSince_ = -1;                      // all fitting continuously since (while reported)
};

}  // namespace xr
