// FastOvSupervisor: Groups 1 and 2 (the voltage's), the load dump, and the
// one cap and slew bypass they and Group 3 set together.
#include "protection/fast_ov.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "params/constants.h"

namespace xr {

void FastOvSupervisor::sample(const Inputs& in, const Params& p) noexcept {
  now_ = in.now;
  IBV_ = in.IBV.value;
  rates_.update(in, p);
}

void FastOvSupervisor::reset() noexcept {
  group3_.reset();
  wasActive_ = false;
  bypassLatched_ = false;
}

const FastOvAction& FastOvSupervisor::update(const FastOvInputs& x, const Params& p) noexcept {
  if (lastCall_ < 0 || now_ - lastCall_ > kGap || now_ < lastCall_) reset();
  const TimeNs prevCall = lastCall_;  // Group 3's bleed step
  lastCall_ = now_;

  FastOvAction& a = action_;
  a = FastOvAction{};
  FastOvVerdict& v = a.verdict;
  const double target = x.ChargingVoltageTarget;
  // nearBulk = (ProtectionProxGateV <= 0) OR (target >= BulkVoltage - ProtectionProxGateV)
  a.nearBulk = p.ProtectionProxGateV <= 0.0 || target >= p.BulkVoltage - p.ProtectionProxGateV;
  const double base = std::max(0.0, x.uTargetAmps);  // fastOvBaseCap
  v.fastOvCurrentCap = base;
  v.cv_I = x.cv_I;

  // FLOAT arms them too, whatever its distance from BulkVoltage: a load dump
  // or a surplus of field in float is as real as in absorption
  // (docs/deviations.md "Fast over-voltage supervisors in float").
  const bool armed = x.voltageControlActive && (a.nearBulk || x.floatStage) && std::isfinite(IBV_);
  if (!armed) {
    // CV inactive or far from bulk: nothing throttles; the CV tracker owns
    // cv_I. The reset empties Group 3's window, so it is fed on armed ticks only.
    reset();
    Vpred_ = std::isfinite(IBV_) ? IBV_ + p.TdPred * std::max(0.0, rates_.dvdt()) : 0.0;
    return a;
  }
  group3_.push(x);
  double cap = wasActive_ ? std::min(cap_, base) : base;
  cap = std::min(cap, voltageGroupsCap(x, p));
  a.loadDump = rates_.loadDump();
  const IExcessResult g3 =
      group3_.update(x, {IBV_, a.group1 || a.group2 || a.loadDump, base, now_, prevCall}, p);
  cap = std::min(cap, g3.cap);
  a.group3 = g3.active;
  if (g3.cvIAction != CvIAction::None) {
    v.cvIAction = g3.cvIAction;
    v.cv_I = g3.cv_I;
  }
  // Load dump (gated on INA fast mode): everything to zero, AW bleed recovers.
  if (a.loadDump) {
    cap = 0.0;
    v.zeroSetpointLimited = true;
    v.cvIAction = CvIAction::Snap;
    v.cv_I = 0.0;
  }
  finish(cap, base, target);
  return a;
}

// Groups 1 and 2, the voltage's: the cap they set (+infinity when neither acts).
double FastOvSupervisor::voltageGroupsCap(const FastOvInputs& x, const Params& p) noexcept {
  const double target = x.ChargingVoltageTarget;
  double cap = std::numeric_limits<double>::infinity();
  // Group 1 - prediction: Vpred = IBV + TdPred * max(0, dvdt).
  Vpred_ = IBV_ + p.TdPred * std::max(0.0, rates_.dvdt());
  const double vHard = target + p.OvPredMarginV;
  if (p.OvGroup1Enable && IBV_ > target - k::PRED_GUARD && Vpred_ > vHard) {
    cap = std::min(cap, x.setpointLimited - p.KHard * (Vpred_ - vHard));
    action_.group1 = true;
  }
  // Group 2 - measured: IBV > target + OvMeasMarginV.
  if (p.OvGroup2Enable && IBV_ > target + p.OvMeasMarginV) {
    cap = std::min(cap, x.setpointLimited - p.KHard * (IBV_ - target - p.OvMeasMarginV));
    action_.group2 = true;
  }
  return cap;
}

// The cap held while any supervisor acts (it only falls), the slew bypass
// and its latch: it releases below target + 0.02 V (docs/control.md "Governor").
void FastOvSupervisor::finish(double cap, double base, double target) noexcept {
  FastOvAction& a = action_;
  const bool any = a.group1 || a.group2 || a.group3 || a.loadDump;
  if (any) {
    cap_ = std::clamp(cap, 0.0, base);
    a.verdict.fastOvCurrentCap = cap_;
    a.verdict.fastOvClampActive = true;
    bypassLatched_ = true;
  } else {
    cap_ = base;
    if (IBV_ < target + k::CV_OVERSHOOT_RELEASE_V) bypassLatched_ = false;
  }
  wasActive_ = any;
  a.verdict.forceBypassSlew = any || bypassLatched_;
}

}  // namespace xr
