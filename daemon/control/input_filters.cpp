// InputFilters: the CH1 record-path filters, the IBV filter and its slope,
// and the tick / control dts (docs/control.md "Feedback filters").
#include "control/input_filters.h"

#include <algorithm>

#include "core/finite.h"

namespace xr {

void InputFilters::update(const ControlSensors& s, const Params& p) noexcept {
  tickDt_ = lastTick_ < 0 ? 0.0 : std::clamp(toSec(s.now - lastTick_), 0.0, kMaxControlDtSec);
  lastTick_ = s.now;
  if (s.ch1Fresh) {
    controlDt_ =
        lastControlTick_ < 0 ? 0.0 : std::clamp(toSec(s.now - lastControlTick_), 0.0, kMaxControlDtSec);
    lastControlTick_ = s.now;
    if (finite(s.MeasuredAmps)) {
      MeasuredAmps_ = s.MeasuredAmps;
      emaInput_.update(s.MeasuredAmps, controlDt_, p.InputFilterTC);
      emaPid_.update(s.MeasuredAmps, controlDt_, p.OutputPIDFilterTC);
      maPid_.update(s.MeasuredAmps, p.OutputPIDMA_N);
    }
  } else {
    controlDt_ = 0.0;
  }
  if (finite(s.Bcur)) emaBcur_.update(s.Bcur, tickDt_, kBcurSlowTcMs);
  if (s.ibvFresh && finite(s.IBV)) {
    const double dt = lastFilterIbvNs_ < 0 ? 0.0 : toSec(s.now - lastFilterIbvNs_);
    emaIBV_.update(s.IBV, dt, p.VoltageFilterTC);
    // cvDSlope between fresh samples, over the time they are apart.
    if (dt > 0.0) ibvSlope_ = (emaIBV_.value() - lastFiltV_) / dt;
    lastFiltV_ = emaIBV_.value();
    lastFilterIbvNs_ = s.now;
  }
  pidSig_ =
      p.OutputPIDSigSrc == 2 ? MeasuredAmps_ : (p.OutputPIDSigSrc == 1 ? maPid_.value() : emaPid_.value());
}

}  // namespace xr
