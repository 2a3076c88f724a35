#include "control/system_id.h"

#include <algorithm>
#include <cmath>

namespace xr {

bool SystemId::start(TimeNs now, const SystemIdSnapshot& pre) noexcept {
  if (running_ || !pre.autoRunning) return false;
  running_ = true;
  stepped_ = false;
  start_ = now;
  pre_ = pre;
  baseSum_ = 0.0;
  baseCount_ = 0;
  n_ = 0;
  result_ = SystemIdResult{};
  return true;
}

double SystemId::systemIdTick(TimeNs now, double measuredAmps, const Params& p, bool& finished) noexcept {
  finished = false;
  if (!running_) return 0.0;
  const TimeNs half = fromMs(p.sysIDDurationMs);
  const TimeNs t = now - start_;
  if (t < half) {
    // Base phase: the steady current before the step (its last half).
    if (t >= half / 2 && std::isfinite(measuredAmps)) {
      baseSum_ += measuredAmps;
      ++baseCount_;
    }
    return p.sysIDBaseDuty;
  }
  if (!stepped_) {
    stepped_ = true;
    stepAt_ = now;
    lastSample_ = now - half;  // sample immediately
  }
  const TimeNs sinceStep = now - stepAt_;
  const TimeNs stride = std::max<TimeNs>(1, half / kSamples);
  if (n_ < kSamples && now - lastSample_ >= stride && std::isfinite(measuredAmps)) {
    amps_[static_cast<std::size_t>(n_)] = static_cast<float>(measuredAmps);
    tMs_[static_cast<std::size_t>(n_)] = static_cast<float>(toMs(sinceStep));
    ++n_;
    lastSample_ = now;
  }
  if (sinceStep >= half) {
    running_ = false;
    finished = true;
    analyse();
    return p.sysIDStepDuty;
  }
  return p.sysIDStepDuty;
}

void SystemId::analyse() noexcept {
  result_ = SystemIdResult{};
  if (baseCount_ == 0 || n_ < 10) return;
  const double I0 = baseSum_ / baseCount_;
  const int tail = std::max(1, n_ / 10);
  double s = 0.0;
  for (int i = n_ - tail; i < n_; ++i) s += amps_[static_cast<std::size_t>(i)];
  const double I1 = s / tail;
  const double dI = I1 - I0;
  result_.I0 = I0;
  result_.I1 = I1;
  if (std::fabs(dI) < 0.5) return;  // no measurable response: report invalid rather than noise
  double t10 = -1, t90 = -1;
  for (int i = 0; i < n_; ++i) {
    const double frac = (amps_[static_cast<std::size_t>(i)] - I0) / dI;
    if (t10 < 0 && frac >= 0.1) t10 = tMs_[static_cast<std::size_t>(i)];
    if (t90 < 0 && frac >= 0.9) {
      t90 = tMs_[static_cast<std::size_t>(i)];
      break;
    }
  }
  if (t10 < 0 || t90 < 0) return;
  result_.valid = true;
  result_.deadTimeMs = t10;
  result_.riseTimeMs = t90 - t10;
  result_.slopeAps = result_.riseTimeMs > 0 ? 0.8 * dI / (result_.riseTimeMs * 1e-3) : 0.0;
}

}  // namespace xr
