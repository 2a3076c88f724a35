// BmsPlausibility (see bms_plausibility.h).
#include "control/bms_plausibility.h"

#include <algorithm>
#include <cmath>

#include "params/derived.h"

namespace xr {

// BatteryCells when set; else the class of BulkVoltage in the profile's
// cells (lead-acid 2 V cells, every other profile lithium: 4 per 12 V).
BankShape bankShape(const Params& p) noexcept {
  const bool leadAcid = p.BatteryProfile >= 1 && p.BatteryProfile <= 3;  // agm, flooded, gel
  BankShape s;
  if (p.BatteryCells > 0) {
    s.cells = p.BatteryCells;
    const double nominalPerCell = leadAcid ? 2.0 : 3.2;
    s.nominalV = nominalVoltage(bankClassOfVoltage(s.cells * nominalPerCell));
  } else {
    s.nominalV = nominalVoltage(systemClass(p));
    s.cells = (leadAcid ? 6 : 4) * s.nominalV / 12;
  }
  return s;
}

bool BmsPlausibility::cellsFit(const BmsLimits& b, double packV, const Params& p) noexcept {
  const bool hiKnown = std::isfinite(b.cellMaxV), loKnown = std::isfinite(b.cellMinV);
  if ((hiKnown && (b.cellMaxV > kCellHighestV || b.cellMaxV < kCellLowestV)) ||
      (loKnown && (b.cellMinV > kCellHighestV || b.cellMinV < kCellLowestV)))
    return false;
  if (!std::isfinite(packV) || packV <= 0.0) return true;
  // The pack's mean cell lies between the lowest and the highest cell (a
  // side the BMS does not send bounds nothing).
  const double mean = packV / bankShape(p).cells;
  return !(hiKnown && mean > b.cellMaxV + kCellFitV) && !(loKnown && mean < b.cellMinV - kCellFitV);
}

BmsMismatch BmsPlausibility::check(const BmsLimits& b, double packV, const Params& p, double* a,
                                   double* bv) noexcept {
  const BankShape bank = bankShape(p);
  auto out = [&](BmsMismatch m, double x, double y) {
    if (a) *a = x;
    if (bv) *bv = y;
    return m;
  };
  if (std::isfinite(b.cvlV) && b.cvlV > 0.0 && nominalVoltage(bankClassOfVoltage(b.cvlV)) != bank.nominalV)
    return out(BmsMismatch::CVL_CLASS, b.cvlV, bank.nominalV);
  if (!cellsFit(b, packV, p))
    return out(BmsMismatch::CELL_VOLTAGE, std::isfinite(b.cellMaxV) ? b.cellMaxV : b.cellMinV,
               std::isfinite(packV) ? packV / bank.cells : kBmsNoValue);
  // Only while the BMS lets the bank charge and raises no alarm: with its
  // contactor open the regulator measures the alternator's bus, not the pack.
  const VoltageRange range = plausibleVoltageRange(p);
  if (std::isfinite(b.voltageV) && b.voltageV > 0.0 && std::isfinite(packV) && b.chargeAllowed &&
      b.alarms == 0 && packV >= range.min && packV <= range.max &&
      std::fabs(b.voltageV - packV) > criticalDisagreementThreshold(p))
    return out(BmsMismatch::PACK_VOLTAGE, b.voltageV, packV);
  const bool highWarn = ((b.warnings | b.alarms) & bmswarn::HighVoltage) != 0;
  if (highWarn && std::isfinite(b.cellMaxV)) {
    const double normal = (p.BmsCellHighV > 0.0 ? p.BmsCellHighV : 3.55) - kCellNormalMarginV;
    const bool packNormal = !std::isfinite(packV) || packV / bank.cells < normal;
    if (b.cellMaxV < normal && packNormal) return out(BmsMismatch::WARNING_CELLS_NORMAL, b.cellMaxV, normal);
  }
  return out(BmsMismatch::NONE, 0.0, 0.0);
}

void BmsPlausibility::reset() noexcept {
  reported_ = BmsMismatch::NONE;
  seenSince_ = fitSince_ = -1;
}

// detail of the BmsMismatch event: the kind in bits 0-3, the bank's cells in
// bits 4-9 and its nominal voltage from bit 10 (describe() names them).
void BmsPlausibility::update(const BmsLimits& b, TimeNs now, double packV, const Params& p,
                             EventBatch& ev) noexcept {
  double a = 0.0, bv = 0.0;
  const BmsMismatch m = check(b, packV, p, &a, &bv);
  const BankShape bank = bankShape(p);
  const int detailBank = (bank.cells << 4) | (bank.nominalV << 10);
  if (m != BmsMismatch::NONE) {
    fitSince_ = -1;
    if (seenSince_ < 0) seenSince_ = now;
    if (reported_ == BmsMismatch::NONE && now - seenSince_ >= fromSec(kConfirmS)) {
      reported_ = m;
      ev.push(makeEvent(now, EventLevel::Warning, EventCode::BmsMismatch, Reason::NONE, a, bv,
                        static_cast<int>(m) | detailBank));
    }
    return;
  }
  seenSince_ = -1;
  if (reported_ == BmsMismatch::NONE) return;
  if (fitSince_ < 0) fitSince_ = now;
  if (now - fitSince_ >= fromSec(kClearS)) {
    ev.push(makeEvent(now, EventLevel::Info, EventCode::BmsMismatch, Reason::NONE,
                      static_cast<double>(reported_), 0.0, detailBank));
    reset();
  }
}

}  // namespace xr
