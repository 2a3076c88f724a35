// BmsLimiter: a BMS's limits as this tick's caps (see bms_limiter.h).
#include "control/bms_limiter.h"

#include <algorithm>
#include <cmath>

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

void BmsLimiter::reset() {
  state_ = BmsState::OFF;
  enabledSince_ = -1;
  cap_ = cvl_ = warnCap_ = kNone;
  chargeAllowed_ = true;
  cellHigh_ = false;
  shownCvl_ = shownCcl_ = shownSoc_ = kBmsNoValue;
}

void BmsLimiter::update(const BmsLimits& b, TimeNs now, double Bcur, const Params& p, EventBatch& ev) {
  const double dt = lastNow_ < 0 ? 0.0 : std::max(0.0, toSec(now - lastNow_));
  lastNow_ = now;
  if (!p.BmsLimitsEnabled) {
    if (state_ == BmsState::STALE)
      ev.push(makeEvent(now, EventLevel::Info, EventCode::ProtectionClear, Reason::REASON_BMS_STALE));
    reset();
    return;
  }
  if (enabledSince_ < 0) enabledSince_ = now;

  // Silent since it was enabled counts as stale too: a BMS that never spoke
  // must not leave the bank uncapped.
  const TimeNs heard = b.stamp != 0 ? b.stamp : enabledSince_;
  const bool stale = now - heard > fromSec(p.BmsStaleS);
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
    shownCvl_ = shownCcl_ = shownSoc_ = kBmsNoValue;
    return;
  }

  // Decoders post only checked values; a non-finite CCL still never uncaps.
  double cap = std::isfinite(b.cclA) && b.cclA >= 0.0 ? b.cclA : p.BmsFallbackCapA;
  cvl_ = std::isfinite(b.cvlV) && b.cvlV > 0.0 ? b.cvlV - p.BmsCvlMarginV : kNone;
  chargeAllowed_ = b.chargeAllowed;

  if (p.BmsCellHighV > 0.0 && std::isfinite(b.cellMaxV)) {
    if (b.cellMaxV >= p.BmsCellHighV)
      cellHigh_ = true;
    else if (b.cellMaxV < p.BmsCellHighV - kCellHysteresisV)
      cellHigh_ = false;
  } else {
    cellHigh_ = false;
  }
  const bool warn = ((b.warnings | b.alarms) & bmswarn::ChargeRampDown) != 0 || cellHigh_;
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

  state_ = !chargeAllowed_ ? BmsState::CHARGE_DISABLED : (warn ? BmsState::WARNING : BmsState::OK);
  shownCvl_ = b.cvlV;
  shownCcl_ = b.cclA;
  shownSoc_ = b.socPct;
}

}  // namespace xr
