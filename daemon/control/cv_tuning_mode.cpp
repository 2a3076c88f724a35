#include "control/cv_tuning_mode.h"

#include <algorithm>
#include <cmath>

#include "params/constants.h"
#include "params/derived.h"

namespace xr {

void CvTuningModeRunner::reset() {
  running_ = high_ = settledThisPhase_ = false;
  ise_ = T_ = settleSum_ = 0.0;
  settleCount_ = consecutive_ = 0;
  lastSettleSec_ = -1.0;
}

double CvTuningModeRunner::target(TimeNs now, double normalTarget, const Params& p) {
  if (!running_) {
    running_ = true;
    start_ = phaseStart_ = now;
    high_ = false;
    ise_ = T_ = 0.0;
  }
  now_ = now;
  const double half = p.cvWavePeriod * 0.5;
  const bool high = half > 0 && static_cast<long long>(std::floor(toSec(now - start_) / half)) % 2 == 1;
  if (high != high_) {
    high_ = high;
    phaseStart_ = now;
    settledThisPhase_ = false;
    consecutive_ = 0;
  }
  // This project's (docs/deviations.md "CVTuningMode high target"): the HIGH phase
  // never asks for more than the hard-shutdown trip less a margin for the
  // loop's overshoot; the specification's 14.5 + 0.2 V sat 0.1 V under a 14.8 V trip.
  // Not set up: never above the charge ceiling (config/setup_pending.h).
  double ceiling = alternatorHardShutdownV(p) - k::CV_TUNING_TRIP_MARGIN_V;
  if (p.SetupCeilingV > 0.0) ceiling = std::min(ceiling, p.SetupCeilingV);
  target_ =
      high_ ? std::max(normalTarget, std::min(normalTarget + p.cvWaveAmplitudeV, ceiling)) : normalTarget;
  return target_;
}

void CvTuningModeRunner::score(double IBV, double dtSec, const Params& p) {
  if (!running_ || !(dtSec > 0.0) || !std::isfinite(IBV)) return;
  const double err = IBV - target_;  // + above target
  const double tPhase = toSec(now_ - phaseStart_);
  double w2 = 0.0;
  if (high_) {
    if (err > 0.0) {
      const double over = std::max(0.0, err - k::CV_HIGH_DEADBAND_V);  // first 25 mV free
      w2 = p.cvKOvershoot * over * over;
    } else {
      w2 = err * err;
    }
  } else {
    if (err > 0.0) {
      w2 = err * err;
    } else {
      const double ramp = std::clamp((tPhase - k::CV_LOW_GRACE_SEC) / k::CV_LOW_RAMP_SEC, 0.0, 1.0);
      w2 = ramp * err * err;
    }
  }
  ise_ += w2 * dtSec;
  T_ += dtSec;
  if (std::fabs(err) <= k::CV_SETTLE_V_THRESH) {
    if (++consecutive_ >= p.cvConsecutiveReads && !settledThisPhase_) {
      settledThisPhase_ = true;
      lastSettleSec_ = tPhase;
      settleSum_ += tPhase;
      ++settleCount_;
    }
  } else {
    consecutive_ = 0;
  }
}

bool CvTuningModeRunner::commit(TimeNs now, const Params& p) {
  if (!running_ || T_ <= 0.0) return false;
  CvTuningRecord r;
  r.t = now;
  r.VoltageKp = p.VoltageKp;
  r.VoltageKi = p.VoltageKi;
  r.cvWaveAmplitudeV = p.cvWaveAmplitudeV;
  r.cvWavePeriod = p.cvWavePeriod;
  r.score = currentScore();
  r.settleSec = settleCount_ ? settleSum_ / settleCount_ : -1.0;
  cvTuningLog_[static_cast<std::size_t>(logHead_)] = r;
  logHead_ = (logHead_ + 1) % k::TUNING_LOG_SIZE;
  if (logCount_ < k::TUNING_LOG_SIZE) ++logCount_;
  ise_ = T_ = settleSum_ = 0.0;
  settleCount_ = 0;
  return true;
}

}  // namespace xr
