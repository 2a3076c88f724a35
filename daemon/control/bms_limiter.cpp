// BmsLimiter: a BMS's limits as this tick's caps (see bms_limiter.h).
#include "control/bms_limiter.h"

#include <algorithm>
#include <cmath>

#include "core/freshness.h"

namespace xr {

std::string_view toString(BmsState s) {
  switch (s) {
    case BmsState::OFF:
      return "OFF";
    case BmsState::OK:
      return "OK";
    case BmsState::WARNING:
      return "WARNING";
    case BmsState::CHARGE_DISABLED:
      return "CHARGE_DISABLED";
    case BmsState::STALE:
      return "STALE";
  }
  return "?";
}

std::string_view toString(BmsSource s) {
  switch (s) {
    case BmsSource::None:
      return "None";
    case BmsSource::Can:
      return "Can";
    case BmsSource::VictronGx:
      return "VictronGx";
    case BmsSource::Sim:
      return "Sim";
  }
  return "None";
}

void BmsLimiter::reset() noexcept {
  state_ = BmsState::OFF;
  enabledSince_ = -1;
  cap_ = cvl_ = warnCap_ = kNone;
  chargeAllowed_ = true;
  cellHigh_ = false;
  cellCeiling_ = kNone;
  shownCvl_ = shownCcl_ = shownSoc_ = kBmsNoValue;
}

void BmsLimiter::update(const BmsLimits& b, TimeNs now, double Bcur, double packV, const Params& p,
                        EventBatch& ev) noexcept {
  const double dt = lastNow_ < 0 ? 0.0 : std::max(0.0, toSec(now - lastNow_));
  lastNow_ = now;
  // No source configured (source None): nothing to follow. A configured one
  // is followed unless the owner chose monitor only (BmsLimitsEnabled = 0).
  if (!p.BmsLimitsEnabled || b.source == BmsSource::None) {
    if (state_ == BmsState::STALE)
      ev.push(makeEvent(now, EventLevel::Info, EventCode::ProtectionClear, Reason::REASON_BMS_STALE));
    reset();
    plausibility_.reset();
    return;
  }
  if (enabledSince_ < 0) enabledSince_ = now;

  // Silent since it was enabled counts as stale too: a BMS that never spoke
  // must not leave the bank uncapped.
  const TimeNs heard = b.stamp != 0 ? b.stamp : enabledSince_;
  const bool stale = !fresh::bms(heard, now, p.BmsStaleS);
  const bool wasStale = state_ == BmsState::STALE;
  if (stale && !wasStale) {
    ev.push(makeEvent(now, EventLevel::Warning, EventCode::ProtectionTrip, Reason::REASON_BMS_STALE,
                      toSec(now - heard), p.BmsStaleS));
  } else if (!stale && wasStale) {
    ev.push(makeEvent(now, EventLevel::Info, EventCode::ProtectionClear, Reason::REASON_BMS_STALE));
  }
  if (stale) {
    state_ = BmsState::STALE;
    cap_ = p.BmsFallbackCapA;
    cvl_ = kNone;           // the configured stage voltages apply
    chargeAllowed_ = true;  // the digital BMS input still protects
    warnCap_ = kNone;
    cellHigh_ = false;
    cellCeiling_ = kNone;
    shownCvl_ = shownCcl_ = shownSoc_ = kBmsNoValue;
    return;
  }

  // Decoders post only checked values; a non-finite CCL still never uncaps.
  double cap = std::isfinite(b.cclA) && b.cclA >= 0.0 ? b.cclA : p.BmsFallbackCapA;
  cvl_ = std::isfinite(b.cvlV) && b.cvlV > 0.0 ? b.cvlV - p.BmsCvlMarginV : kNone;
  chargeAllowed_ = b.chargeAllowed;

  // Every value against the bank; cell readings that do not fit (a BMS set
  // up for another cell count) never drive the ceiling.
  plausibility_.update(b, now, packV, p, ev);
  if (BmsPlausibility::cellsFit(b, packV, p)) {
    updateCellCeiling(b, packV, dt, p);
  } else {
    BmsLimits noCells = b;
    noCells.cellMaxV = noCells.cellMinV = kBmsNoValue;
    updateCellCeiling(noCells, packV, dt, p);
  }
  const bool warn = ((b.warnings | b.alarms) & bmswarn::ChargeRampDown) != 0;
  if (warn) {
    if (warnCap_ == kNone) {
      // Start from the current flowing now, so the ramp has no step, and
      // reach 0 in BmsWarnRampS whatever that current is.
      const double from = std::isfinite(Bcur) ? Bcur : p.MaximumAllowedBatteryAmps;
      warnCap_ = std::clamp(from, 0.0, std::min(cap, p.MaximumAllowedBatteryAmps));
      warnRate_ = std::max(warnCap_, 1.0) / p.BmsWarnRampS;
    }
    warnCap_ = std::max(0.0, warnCap_ - warnRate_ * dt);
  } else if (warnCap_ != kNone) {
    warnCap_ += warnRate_ * dt;
    if (warnCap_ >= std::min(cap, p.MaximumAllowedBatteryAmps)) warnCap_ = kNone;
  }
  cap_ = std::min(cap, warnCap_);
  cvl_ = std::min(cvl_, cellCeiling_);

  state_ = !chargeAllowed_ ? BmsState::CHARGE_DISABLED : (warn ? BmsState::WARNING : BmsState::OK);
  shownCvl_ = b.cvlV;
  shownCcl_ = b.cclA;
  shownSoc_ = b.socPct;
}

// Cells in series: the configured count, else the pack over its mean cell
// (a custom profile leaves BatteryCells at 0).
double BmsLimiter::cellsInSeries(const BmsLimits& b, double packV, const Params& p) noexcept {
  if (p.BatteryCells > 0) return p.BatteryCells;
  const double meanCell =
      std::isfinite(b.cellMinV) && b.cellMinV > 0.0 ? (b.cellMaxV + b.cellMinV) / 2.0 : b.cellMaxV;
  return std::clamp(std::round(packV / meanCell), 1.0, 32.0);
}

// A constant voltage on the highest cell: the pack voltage that holds that
// cell at BmsCellHighV is not known (the full cell rises faster than the
// others), so the ceiling is trimmed by the cell's error, an integrator of
// time constant kCellTrimTauS in cell terms. It starts at the pack voltage
// of the moment the cell first reaches the limit (no step) and ends once
// the ceiling has risen kCellReleaseV above the pack: nothing holds it then
// (docs/integrations.md "Cell voltages").
void BmsLimiter::updateCellCeiling(const BmsLimits& b, double packV, double dt, const Params& p) noexcept {
  if (p.BmsCellHighV <= 0.0 || !std::isfinite(b.cellMaxV) || b.cellMaxV <= 0.0) {
    cellCeiling_ = kNone;
    cellHigh_ = false;
    return;
  }
  if (!std::isfinite(packV)) return;               // a tick without IBV: the ceiling holds where it was
  const double err = p.BmsCellHighV - b.cellMaxV;  // > 0: the cell is under its limit
  if (cellCeiling_ == kNone) {
    if (err > 0.0) return;
    cellCeiling_ = packV;
  }
  cellCeiling_ += cellsInSeries(b, packV, p) * err * dt / kCellTrimTauS;
  cellCeiling_ = std::max(cellCeiling_, packV - kCellMaxStepV);  // never far under the pack: no field cut
  if (cellCeiling_ > packV + kCellReleaseV) cellCeiling_ = kNone;
  cellHigh_ = cellCeiling_ != kNone;
}

}  // namespace xr
