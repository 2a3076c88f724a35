// BeltSlipDetector (docs/operations.md "Belt slip").
#include "health/belt_slip.h"

#include <algorithm>
#include <cmath>

namespace xr {

using namespace belt_k;

bool BeltSlipDetector::update(TimeNs now, double dt_s, const BeltSample& s, EventBatch& ev) noexcept {
  if (!(dt_s > 0.0)) return false;
  const bool engineKnown = std::isfinite(s.engineRpm);
  auto add = [&](double& acc, double v) { acc += std::isfinite(v) ? v * dt_s : 0.0; };
  add(acc_.rpm, s.rpm);
  add(acc_.amps, s.altAmps);
  add(acc_.duty, s.dutyPct);
  add(acc_.target, s.targetAmps);
  if (engineKnown) acc_.engine += s.engineRpm * dt_s;
  ratedA_ = s.ratedA;
  engineHeard_ = s.engineHeard;
  // A second counts as "field on" / "engine heard" only if every tick of it was.
  acc_.field = accT_ == 0.0 ? s.fieldOn : acc_.field && s.fieldOn;
  acc_.engineKnown = accT_ == 0.0 ? engineKnown : acc_.engineKnown && engineKnown;
  accT_ += dt_s;
  if (accT_ < 1.0 - 1e-6) return false;  // a second of ticks, whatever their rounding
  return closeSecond(now, ev);
}

bool BeltSlipDetector::closeSecond(TimeNs now, EventBatch& ev) noexcept {
  Second s = acc_;
  s.rpm /= accT_;
  s.engine /= accT_;
  s.amps /= accT_;
  s.duty /= accT_;
  s.target /= accT_;
  acc_ = Second{};
  accT_ = 0.0;
  ring_[next_] = s;
  next_ = (next_ + 1) % kWindowS;
  filled_ = std::min(filled_ + 1, kWindowS);

  double slipPct = 0.0, dropA = 0.0, riseDuty = 0.0, risePct = 0.0, ampsBefore = 0.0;
  const bool a = ratioSign(s, slipPct);
  const bool b = currentSign(dropA, riseDuty);
  const bool c = !a && !b && probeSign(risePct, ampsBefore);
  if (c) {
    if (latched_) return false;
    latched_ = true;
    quietS_ = 0.0;
    ev.push(makeEvent(now, EventLevel::Warning, EventCode::BeltSlip, Reason::NONE, risePct, ampsBefore, 3));
    return true;
  }
  if (!a && !b && lowS_ == 0) {
    quietS_ += 1.0;
    if (quietS_ >= kRearmS) latched_ = false;
    return false;
  }
  quietS_ = 0.0;
  if (latched_ || (!a && !b)) return false;
  latched_ = true;
  if (a)
    ev.push(makeEvent(now, EventLevel::Warning, EventCode::BeltSlip, Reason::NONE, slipPct, s.engine, 1));
  else
    ev.push(makeEvent(now, EventLevel::Warning, EventCode::BeltSlip, Reason::NONE, dropA, riseDuty, 2));
  return true;
}

// A: the tach against the engine. The ratio is learned while it is not low.
bool BeltSlipDetector::ratioSign(const Second& s, double& slipPct) noexcept {
  if (!s.engineKnown || !s.field || s.engine < kMinRpm || !(s.rpm > 0.0)) {
    lowS_ = 0;
    return false;
  }
  const double r = s.rpm / s.engine;
  if (ratio_ == 0.0) {
    learnSum_ += r;
    if (++learnS_ >= kLearnFirstS) ratio_ = learnSum_ / learnS_;
    return false;
  }
  const bool low = r < ratio_ * (1.0 - kSlipShare);
  if (!low) {
    lowS_ = 0;
    ratio_ += (r - ratio_) / kLearnTauS;
    return false;
  }
  // The engine steady over the hold: a speed change lags the tach's filter.
  ++lowS_;
  if (lowS_ < kHoldS || filled_ < kHoldS) return false;
  double lo = ago(0).engine, hi = lo;
  for (int i = 1; i < kHoldS; ++i) {
    lo = std::min(lo, ago(i).engine);
    hi = std::max(hi, ago(i).engine);
  }
  if (hi - lo > kSteadyShare * hi) return false;
  slipPct = 100.0 * (1.0 - r / ratio_);
  return true;
}

// B: current down, duty up, speed steady, over the whole window.
bool BeltSlipDetector::currentSign(double& dropA, double& riseDuty) const noexcept {
  if (filled_ < kWindowS) return false;
  double lo = ago(0).rpm, hi = lo;
  for (int i = 0; i < kWindowS; ++i) {
    const Second& x = ago(i);
    if (!x.field) return false;
    lo = std::min(lo, x.rpm);
    hi = std::max(hi, x.rpm);
  }
  if (lo < kMinRpm || hi - lo > kSteadyShare * hi) return false;
  const Second& now = ago(0);
  const Second& then = ago(kWindowS - 1);
  dropA = then.amps - now.amps;
  riseDuty = now.duty - then.duty;
  return riseDuty >= kDutyRise && dropA >= std::max(kCurrentDropA, kCurrentDropShare * then.amps) &&
         now.target - now.amps >= kWantMoreA;
}

}  // namespace xr
