#include "store/charge_tally.h"

#include <algorithm>

namespace xr {

namespace {

double* stageSeconds(ChargeStage stage, double& bulk, double& absorption, double& flt) {
  switch (stage) {
    case ChargeStage::BULK:
      return &bulk;
    case ChargeStage::ABSORPTION:
      return &absorption;
    case ChargeStage::FLOAT:
      return &flt;
    case ChargeStage::IDLE:
      return nullptr;
  }
  return nullptr;
}

// max/min that treat NaN as "nothing yet".
double maxKnown(double a, double b) { return std::isnan(a) ? b : std::isnan(b) ? a : std::max(a, b); }
double minKnown(double a, double b) { return std::isnan(a) ? b : std::isnan(b) ? a : std::min(a, b); }
double orZero(double v) { return std::isfinite(v) ? v : 0.0; }

}  // namespace

ChargeTally::Ended ChargeTally::add(const TallySample& s) {
  Ended out;
  double dt = 0.0;
  if (lastMs_) dt = static_cast<double>(s.unixMs - *lastMs_) / 1000.0;
  if (!(dt > 0.0 && dt <= maxStepS_)) dt = 0.0;
  lastMs_ = s.unixMs;
  if (s.day != day_.day) {
    if (!day_.day.empty()) out.day = day_;
    day_ = DaySummary{};
    day_.day = s.day;
  }
  addToDay(s, dt);
  out.charge = addToCharge(s, dt);
  return out;
}

void ChargeTally::addToDay(const TallySample& s, double dt) {
  const double hours = dt / 3600.0;
  if (s.fieldOn) {
    day_.altAh += orZero(s.altA) * hours;
    day_.altWh += orZero(s.altA) * orZero(s.batteryV) * hours;
    day_.fieldOnS += dt;
    if (double* b = stageSeconds(s.stage, day_.bulkS, day_.absorptionS, day_.floatS)) *b += dt;
  }
  if (s.stage == ChargeStage::IDLE && !s.fieldOn) day_.idleS += dt;
  const double ba = orZero(s.batteryA);
  (ba >= 0.0 ? day_.batteryAhIn : day_.batteryAhOut) += std::abs(ba) * hours;
  if (ba > 0.0) day_.batteryWhIn += ba * orZero(s.batteryV) * hours;
  day_.engineS = orZero(day_.engineS) + (s.engineRunning ? dt : 0.0);
  day_.peakAltTempC = maxKnown(day_.peakAltTempC, s.altTempC);
  day_.minSocPct = minKnown(day_.minSocPct, s.socPct);
  day_.maxSocPct = maxKnown(day_.maxSocPct, s.socPct);
  // A battery voltage of 0 or less is no reading (a sensor not answering).
  const double v = s.batteryV > 0.0 ? s.batteryV : NAN;
  day_.minBatteryV = minKnown(day_.minBatteryV, v);
  day_.maxBatteryV = maxKnown(day_.maxBatteryV, v);
  if (std::isnan(day_.socStartPct)) day_.socStartPct = s.socPct;
  if (!std::isnan(s.socPct)) day_.socEndPct = s.socPct;
}

std::optional<ChargeSummary> ChargeTally::addToCharge(const TallySample& s, double dt) {
  if (s.fieldOn) {
    fieldOffSinceMs_.reset();
    if (!charge_) {
      charge_ = ChargeSummary{};
      charge_->startMs = charge_->endMs = s.unixMs;
      charge_->startSocPct = s.socPct;
    }
    ChargeSummary& c = *charge_;
    c.endMs = s.unixMs;
    c.endSocPct = std::isnan(s.socPct) ? c.endSocPct : s.socPct;
    c.altAh += orZero(s.altA) * dt / 3600.0;
    c.altWh += orZero(s.altA) * orZero(s.batteryV) * dt / 3600.0;
    if (double* b = stageSeconds(s.stage, c.bulkS, c.absorptionS, c.floatS)) *b += dt;
    return std::nullopt;
  }
  if (!charge_) return std::nullopt;
  if (!fieldOffSinceMs_) {
    // Why it stopped is the reason at the moment the field went off.
    fieldOffSinceMs_ = s.unixMs;
    offReason_ = s.reason;
  }
  if (s.unixMs - *fieldOffSinceMs_ < kChargeGapMs) return std::nullopt;
  ChargeSummary done = *charge_;
  done.open = false;
  done.endReason = std::string(toString(offReason_));
  charge_.reset();
  fieldOffSinceMs_.reset();
  return done;
}

}  // namespace xr
