// runFastOvSupervisors(): the voltage OV throttling protections of
// docs/protections.md — Group 1 (prediction), Group 2 (measured),
// Group 3 (iExcess) and load dump — all armed by the nearBulk gate and
// voltageControlActive, all acting through fastOvCurrentCap /
// fastOvClampActive and GOV_BYPASS_SLEW.
#include <algorithm>
#include <cmath>
#include <limits>

#include "params/constants.h"
#include "protection/protection_supervisor.h"

namespace xr {
namespace {
// A gap longer than this between calls (another mode ran) starts the
// supervisors clean: their counters describe consecutive control ticks.
constexpr TimeNs kFastOvGap = fromMs(100);
}  // namespace

void ProtectionSupervisor::resetFastOv() noexcept {
  iexCount_ = 0;
  iexActive_ = false;
  preEventCvI_ = 0.0;
  postFastOvGate_ = false;
  fastOvWasActive_ = false;
  govBypassLatched_ = false;
  maCount_ = 0;
  maHead_ = 0;
}

FastOvAction ProtectionSupervisor::runFastOvSupervisors(const FastOvInputs& x) noexcept {
  if (lastFastOvCall_ < 0 || now_ - lastFastOvCall_ > kFastOvGap || now_ < lastFastOvCall_) resetFastOv();
  // The step since the last call is needed only by the Group 3 bleed; it is
  // computed there from this (the same value as computing it here).
  const TimeNs prevCall = lastFastOvCall_;
  lastFastOvCall_ = now_;

  FastOvAction a;
  const double target = x.ChargingVoltageTarget;
  // nearBulk = (ProtectionProxGateV <= 0) OR (target >= BulkVoltage - ProtectionProxGateV)
  a.nearBulk = p_.ProtectionProxGateV <= 0.0 || target >= p_.BulkVoltage - p_.ProtectionProxGateV;
  const double base = std::max(0.0, x.uTargetAmps);  // fastOvBaseCap
  a.fastOvCurrentCap = base;
  a.cv_I = x.cv_I;

  // Ours (docs/deviations.md "Fast over-voltage supervisors in float"): FLOAT
  // arms them too, whatever its distance from BulkVoltage. A load dump or a
  // surplus of field in float is as real as in absorption.
  const bool armed = x.voltageControlActive && (a.nearBulk || x.floatStage) && std::isfinite(IBV_);
  if (!armed) {
    // CV inactive or far from bulk: nothing throttles; the CV tracker owns cv_I.
    // resetFastOv() empties the Group 3 window (maCount_ = maHead_ = 0), so a
    // sample pushed on this tick could never be read: the window is fed only
    // on armed ticks below, with the same contents wherever it is read.
    resetFastOv();
    Vpred_ = std::isfinite(IBV_) ? IBV_ + p_.TdPred * std::max(0.0, dvdt_) : 0.0;
    lastFastOv_ = a;
    return a;
  }
  pushGroup3Sample(x);
  double cap = fastOvWasActive_ ? std::min(fastOvCap_, base) : base;
  cap = std::min(cap, voltageGroupsCap(x, a));
  const bool loadDump = loadDumpFiredThisSample_ && inaFastModeActive_;
  if (a.group1 || a.group2 || loadDump) postFastOvGate_ = true;
  cap = std::min(cap, runGroup3(x, loadDump, prevCall, base, a));

  // Load dump (gated on INA fast mode): everything to zero, AW bleed recovers.
  if (loadDump) {
    a.loadDump = true;
    cap = 0.0;
    a.zeroSetpointLimited = true;
    a.cvIAction = CvIAction::Snap;
    a.cv_I = 0.0;
  }
  const bool any = a.group1 || a.group2 || a.group3 || a.loadDump;
  if (any) {
    fastOvCap_ = std::clamp(cap, 0.0, base);
    a.fastOvCurrentCap = fastOvCap_;
    a.fastOvClampActive = true;
    govBypassLatched_ = true;
  } else {
    fastOvCap_ = base;
    // CV overshoot bypass latch releases below target + 0.02 V (docs/control.md "Governor").
    if (IBV_ < target + k::CV_OVERSHOOT_RELEASE_V) govBypassLatched_ = false;
  }
  fastOvWasActive_ = any;
  a.forceBypassSlew = any || govBypassLatched_;
  lastFastOv_ = a;
  return a;
}

// Group 3 signal window: every fresh sample since the last reset.
void ProtectionSupervisor::pushGroup3Sample(const FastOvInputs& x) noexcept {
  if (!x.altCurrentFresh || !std::isfinite(x.MeasuredAmps)) return;
  maBuf_[static_cast<std::size_t>(maHead_)] = x.MeasuredAmps;
  maHead_ = (maHead_ + 1) % static_cast<int>(maBuf_.size());
  maCount_ = std::min(maCount_ + 1, static_cast<int>(maBuf_.size()));
}

// Groups 1 and 2, the voltage's: the cap they set (+infinity when neither acts).
double ProtectionSupervisor::voltageGroupsCap(const FastOvInputs& x, FastOvAction& a) noexcept {
  const double target = x.ChargingVoltageTarget;
  double cap = std::numeric_limits<double>::infinity();
  // Group 1 — prediction: Vpred = IBV + TdPred * max(0, dvdt).
  Vpred_ = IBV_ + p_.TdPred * std::max(0.0, dvdt_);
  const double vHard = target + p_.OvPredMarginV;
  if (p_.OvGroup1Enable && IBV_ > target - k::PRED_GUARD && Vpred_ > vHard) {
    cap = std::min(cap, x.setpointLimited - p_.KHard * (Vpred_ - vHard));
    a.group1 = true;
  }
  // Group 2 — measured: IBV > target + OvMeasMarginV.
  if (p_.OvGroup2Enable && IBV_ > target + p_.OvMeasMarginV) {
    cap = std::min(cap, x.setpointLimited - p_.KHard * (IBV_ - target - p_.OvMeasMarginV));
    a.group2 = true;
  }
  return cap;
}

// Group 3's signal (IExcessSigSrc): the window's mean, the filtered or the raw current.
double ProtectionSupervisor::group3Signal(const FastOvInputs& x) const noexcept {
  if (p_.IExcessSigSrc == 1) return x.MeasuredAmps_filtered;
  if (p_.IExcessSigSrc != 0) return x.MeasuredAmps;
  const int maN = std::clamp(p_.IExcessMA_N, 1, static_cast<int>(maBuf_.size()));
  const int n = std::min(maN, maCount_);
  if (n <= 0) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  const int size = static_cast<int>(maBuf_.size());
  for (int i = 1; i <= n; ++i) sum += maBuf_[static_cast<std::size_t>((maHead_ - i + size) % size)];
  return sum / n;
}

// Group 3 — iExcess: current above the setpoint near the voltage target.
// Sets cv_I's action; returns its cap (+infinity when it does not act).
double ProtectionSupervisor::runGroup3(const FastOvInputs& x, bool loadDump, TimeNs prevCall, double base,
                                       FastOvAction& a) noexcept {
  const double target = x.ChargingVoltageTarget;
  const double sig = group3Signal(x);
  const double thr = x.setpointLimited + p_.IExcessK;
  // Post-fastOV mismatch gate: Group 3 waits until current is back within IExcessK.
  if (postFastOvGate_ && !(a.group1 || a.group2 || loadDump) && std::isfinite(sig) && sig <= thr)
    postFastOvGate_ = false;
  const bool vGate = IBV_ > target - p_.OvMeasMarginV;
  if (!iexActive_) {
    if (vGate && !postFastOvGate_ && std::isfinite(sig) && sig > thr) {
      if (++iexCount_ >= p_.IExcessN) {
        iexActive_ = true;
        preEventCvI_ = x.cv_I;
        if (p_.IExcessKBleed <= 0.0) {
          a.cvIAction = CvIAction::Snap;
          a.cv_I = 0.0;
        }
      }
    } else {
      iexCount_ = 0;
    }
  } else if (!std::isfinite(sig) || sig < thr - k::IEXCESS_HYST) {
    // Release with hysteresis, reseed so the loop does not bounce back.
    iexActive_ = false;
    iexCount_ = 0;
    a.cvIAction = CvIAction::Reseed;
    a.cv_I = preEventCvI_ * p_.IExcessReseedFrac;
  }
  if (!iexActive_) return std::numeric_limits<double>::infinity();
  const double excess = std::max(0.0, sig - x.setpointLimited);
  if (p_.IExcessKBleed > 0.0) {
    a.cvIAction = CvIAction::Bleed;
    const double dt = prevCall >= 0 ? std::clamp(toSec(now_ - prevCall), 0.0, 0.1) : 0.0;
    a.cv_I = std::max(0.0, x.cv_I - p_.IExcessKBleed * excess * dt);
  }
  a.group3 = true;
  return std::max(0.0, base - k::K_IE * excess);
}

}  // namespace xr
