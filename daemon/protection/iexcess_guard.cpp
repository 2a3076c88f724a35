// IExcessGuard: Group 3's window, trigger, release and cv_I actions.
#include "protection/iexcess_guard.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "params/constants.h"
#include "protection/fast_ov.h"

namespace xr {

void IExcessGuard::reset() noexcept {
  over_ = 0;
  active_ = false;
  preEventCvI_ = 0.0;
  postFastOvGate_ = false;
  count_ = 0;
  head_ = 0;
}

// Group 3 signal window: every fresh sample since the last reset.
void IExcessGuard::push(const FastOvInputs& x) noexcept {
  if (!x.altCurrentFresh || !std::isfinite(x.MeasuredAmps)) return;
  window_[static_cast<std::size_t>(head_)] = x.MeasuredAmps;
  head_ = (head_ + 1) % static_cast<int>(window_.size());
  count_ = std::min(count_ + 1, static_cast<int>(window_.size()));
}

// Group 3's signal (IExcessSigSrc): the window's mean, the filtered or the raw current.
double IExcessGuard::signal(const FastOvInputs& x, const Params& p) const noexcept {
  if (p.IExcessSigSrc == 1) return x.MeasuredAmps_filtered;
  if (p.IExcessSigSrc != 0) return x.MeasuredAmps;
  const int maN = std::clamp(p.IExcessMA_N, 1, static_cast<int>(window_.size()));
  const int n = std::min(maN, count_);
  if (n <= 0) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  const int size = static_cast<int>(window_.size());
  for (int i = 1; i <= n; ++i) sum += window_[static_cast<std::size_t>((head_ - i + size) % size)];
  return sum / n;
}

// Current above the setpoint near the voltage target: fires after IExcessN
// ticks, releases with hysteresis and reseeds cv_I so the loop does not
// bounce back.
IExcessResult IExcessGuard::update(const FastOvInputs& x, const IExcessContext& c, const Params& p) noexcept {
  IExcessResult r;
  r.cap = std::numeric_limits<double>::infinity();
  r.cv_I = x.cv_I;
  if (c.fastOvActed) postFastOvGate_ = true;
  const double sig = signal(x, p);
  const double thr = x.setpointLimited + p.IExcessK;
  // Post-fastOV mismatch gate: Group 3 waits until current is back within IExcessK.
  if (postFastOvGate_ && !c.fastOvActed && std::isfinite(sig) && sig <= thr) postFastOvGate_ = false;
  const bool vGate = c.IBV > x.ChargingVoltageTarget - p.OvMeasMarginV;
  if (!active_) {
    if (vGate && !postFastOvGate_ && std::isfinite(sig) && sig > thr) {
      if (++over_ >= p.IExcessN) {
        active_ = true;
        preEventCvI_ = x.cv_I;
        if (p.IExcessKBleed <= 0.0) {
          r.cvIAction = CvIAction::Snap;
          r.cv_I = 0.0;
        }
      }
    } else {
      over_ = 0;
    }
  } else if (!std::isfinite(sig) || sig < thr - k::IEXCESS_HYST) {
    active_ = false;
    over_ = 0;
    r.cvIAction = CvIAction::Reseed;
    r.cv_I = preEventCvI_ * p.IExcessReseedFrac;
  }
  if (!active_) return r;
  const double excess = std::max(0.0, sig - x.setpointLimited);
  if (p.IExcessKBleed > 0.0) {
    r.cvIAction = CvIAction::Bleed;
    const double dt = c.prevCall >= 0 ? std::clamp(toSec(c.now - c.prevCall), 0.0, 0.1) : 0.0;
    r.cv_I = std::max(0.0, x.cv_I - p.IExcessKBleed * excess * dt);
  }
  r.active = true;
  r.cap = std::max(0.0, c.base - k::K_IE * excess);
  return r;
}

}  // namespace xr
