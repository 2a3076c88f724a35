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
//   a high cell  : a highest cell voltage (REC's 0x373) at BmsCellHighV or
//                  above acts as a warning (the same ramp) until that cell
//                  is kCellHysteresisV under it: the charge eases off on
//                  the first full cell, before the BMS's own cell limit
//   stale        : no limits for BmsStaleS (or none since BmsLimitsEnabled):
//                  the cap is BmsFallbackCapA, CVL is dropped, REASON_BMS_STALE
//                  with an event on each edge (the alarm row reads stale())
#include <cstdint>
#include <limits>
#include <string_view>

#include "core/bms_limits.h"
#include "core/events.h"
#include "params/params.h"

namespace xr {

// bms_state telemetry column.
enum class BmsState : std::uint8_t { OFF, OK, WARNING, CHARGE_DISABLED, STALE };
std::string_view toString(BmsState s);

class BmsLimiter {
 public:
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  // How far under BmsCellHighV the high cell must fall before the charge
  // ramps back up: an LFP cell relaxes by tens of mV when its current
  // stops, so a smaller band would restart the ramp at once.
  static constexpr double kCellHysteresisV = 0.05;

  // Once per tick, before the charging stage. Bcur = the corrected INA228
  // battery current (NaN when unknown): where a warning ramp starts.
  void update(const BmsLimits& b, TimeNs now, double Bcur, const Params& p, EventBatch& ev);

  double batteryCapA() const { return cap_; }  // kNone when nothing caps
  double cvlCeilingV() const { return cvl_; }  // kNone when nothing caps
  bool chargeAllowed() const { return chargeAllowed_; }
  bool stale() const { return state_ == BmsState::STALE; }
  bool cellHigh() const { return cellHigh_; }
  BmsState state() const { return state_; }
  // The last BMS values for telemetry (NaN when none or stale).
  double shownCvlV() const { return shownCvl_; }
  double shownCclA() const { return shownCcl_; }
  double shownSocPct() const { return shownSoc_; }

 private:
  void reset();

  BmsState state_ = BmsState::OFF;
  TimeNs enabledSince_ = -1;
  TimeNs lastNow_ = -1;
  double cap_ = kNone, cvl_ = kNone;
  double warnCap_ = kNone;  // the warning ramp (kNone = not ramping)
  double warnRate_ = 0.0;   // A/s of that ramp
  bool chargeAllowed_ = true;
  bool cellHigh_ = false;
  double shownCvl_ = kBmsNoValue, shownCcl_ = kBmsNoValue, shownSoc_ = kBmsNoValue;
};

}  // namespace xr
