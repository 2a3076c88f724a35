#include "control/tuning_mode.h"

#include <cmath>

namespace xr {

void TuningModeRunner::reset() {
  running_ = high_ = scoringOpen_ = haveLast_ = false;
  ise_ = scoredSec_ = 0.0;
}

double TuningModeRunner::waveTarget(TimeNs now, const Params& p) {
  if (!running_) {
    running_ = true;
    start_ = now;
    ise_ = scoredSec_ = 0.0;
    haveLast_ = false;
  }
  const double half = p.wavePeriod * 0.5;
  const double tIn = toSec(now - start_);
  high_ = half > 0 && static_cast<long long>(std::floor(tIn / half)) % 2 == 1;
  return k::TUNING_BASE_A + (high_ ? p.waveAmplitude : 0.0);
}

void TuningModeRunner::score(double setpointLimited, double measuredAmps, double dtSec) {
  if (!running_ || !(dtSec > 0.0)) return;
  const double slew = haveLast_ ? std::fabs(setpointLimited - lastSetpoint_) / dtSec : 1e9;
  lastSetpoint_ = setpointLimited;
  haveLast_ = true;
  scoringOpen_ = slew < k::TUNING_SCORE_SLEW_A_PER_S;
  if (!scoringOpen_ || !std::isfinite(measuredAmps)) return;
  const double e = setpointLimited - measuredAmps;
  ise_ += e * e * dtSec;
  scoredSec_ += dtSec;
}

bool TuningModeRunner::commit(TimeNs now, const Params& p) {
  if (!running_ || scoredSec_ <= 0.0) return false;
  TuningRecord r;
  r.t = now;
  r.PidKp = p.PidKp;
  r.PidKi = p.PidKi;
  r.PidKd = p.PidKd;
  r.waveAmplitude = p.waveAmplitude;
  r.wavePeriod = p.wavePeriod;
  r.score = currentScore();
  r.scoredSec = scoredSec_;
  tuningLog_[static_cast<std::size_t>(logHead_)] = r;
  logHead_ = (logHead_ + 1) % k::TUNING_LOG_SIZE;
  if (logCount_ < k::TUNING_LOG_SIZE) ++logCount_;
  ise_ = scoredSec_ = 0.0;  // next record scores afresh
  return true;
}

}  // namespace xr
