#pragma once
// BmsLimiter: turns a BMS's BmsLimits (core/bms_limits.h) into the limits the
// control law applies this tick. Pure: time comes in, nothing is allocated.
//
//   fresh limits : CVL (less BmsCvlMarginV) caps the voltage target; CCL caps
//                  the battery current; chargeAllowed = false disables the
//                  field (REASON_BMS_DISABLED, the digital input's path)
//   a warning    : the battery-current cap ramps from the present battery
//                  current to 0 over BmsWarnRampS (and back up once cleared),
//                  so the charge stops smoothly before the BMS opens
//   a high cell  : a highest cell voltage (REC's 0x373) at BmsCellHighV
//                  puts a ceiling on the voltage target that holds that cell
//                  at the limit (a constant voltage on the highest cell, no
//                  on/off), before the BMS's own cell limit
//   not fitting  : values that do not fit the bank (bms_plausibility.h) are
//                  told once per episode; cell readings that do not fit
//                  are not followed by the highest cell's ceiling
//   no source    : BmsLimits::source None (nothing configured): OFF
//   stale        : no limits for BmsStaleS (or none since the source was
//                  configured):
//                  the cap is BmsFallbackCapA, CVL is dropped, REASON_BMS_STALE
//                  with an event on each edge (the alarm row reads stale())
#include <cstdint>
#include <limits>
#include <string_view>

#include "control/bms_plausibility.h"
#include "core/bms_limits.h"
#include "core/events.h"
#include "params/params.h"

namespace xr {

// bms_state telemetry column.
enum class BmsState : std::uint8_t { OFF, OK, WARNING, CHARGE_DISABLED, STALE };
std::string_view toString(BmsState s);
std::string_view toString(BmsSource s);  // "None", "Can", "VictronGx", "Sim"

class BmsLimiter {
 public:
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  // The highest cell's constant voltage (updateCellCeiling): the trim's
  // time constant in cell terms, how far under the pack the ceiling may go
  // (it trims, it never cuts the field), and how far above the pack it ends.
  static constexpr double kCellTrimTauS = 20.0;
  static constexpr double kCellMaxStepV = 0.3;
  static constexpr double kCellReleaseV = 0.2;

  // Once per tick, before the charging stage. Bcur = the corrected INA228
  // battery current (NaN when unknown): where a warning ramp starts; packV =
  // IBV (NaN when unknown): where the highest cell's ceiling starts.
  void update(const BmsLimits& b, TimeNs now, double Bcur, double packV, const Params& p,
              EventBatch& ev) noexcept;

  double batteryCapA() const noexcept { return cap_; }  // kNone when nothing caps
  double cvlCeilingV() const noexcept { return cvl_; }  // kNone when nothing caps
  bool chargeAllowed() const noexcept { return chargeAllowed_; }
  bool stale() const noexcept { return state_ == BmsState::STALE; }
  bool cellHigh() const noexcept { return cellHigh_; }
  BmsState state() const noexcept { return state_; }
  const BmsPlausibility& plausibility() const noexcept { return plausibility_; }
  // The last BMS values for telemetry (NaN when none or stale).
  double shownCvlV() const noexcept { return shownCvl_; }
  double shownCclA() const noexcept { return shownCcl_; }
  double shownSocPct() const noexcept { return shownSoc_; }

 private:
  void reset() noexcept;
  void updateCellCeiling(const BmsLimits& b, double packV, double dt, const Params& p) noexcept;
  static double cellsInSeries(const BmsLimits& b, double packV, const Params& p) noexcept;

  BmsState state_ = BmsState::OFF;    // OFF / OK / WARNING / ALARM / STALE
  TimeNs enabledSince_ = -1;          // when the BMS was first heard (-1: never)
  TimeNs lastNow_ = -1;               // the last update (the ramp's dt)
  double cap_ = kNone, cvl_ = kNone;  // the battery-current cap and voltage ceiling of this tick
  double warnCap_ = kNone;            // the warning ramp (kNone = not ramping)
  double warnRate_ = 0.0;             // A/s of that ramp
  bool chargeAllowed_ = true;         // the BMS allows charging
  bool cellHigh_ = false;             // the highest cell holds the ceiling
  double cellCeiling_ = kNone;        // the highest cell's pack ceiling (kNone = not holding)
  BmsPlausibility
      plausibility_;  // the BMS's values against the bank (docs/protections.md "BMS plausibility")
  double shownCvl_ = kBmsNoValue, shownCcl_ = kBmsNoValue, shownSoc_ = kBmsNoValue;  // what the screens show
};

}  // namespace xr
