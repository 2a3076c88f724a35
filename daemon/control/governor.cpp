#include "control/governor.h"

#include <algorithm>
#include <cmath>

#include "control/slew.h"

namespace xr {

double governorApplyShutdown(double lastApplied, double target, GovMode govMode, double rampRate,
                             double dtSec, double maxDuty) {
  const double hardMax = std::clamp(maxDuty, 0.0, 100.0);
  const double tgt = std::clamp(std::isfinite(target) ? target : 0.0, 0.0, hardMax);
  const double last = std::isfinite(lastApplied) ? std::clamp(lastApplied, 0.0, hardMax) : 0.0;
  if (govMode == GovMode::GOV_BYPASS_SLEW) return tgt;
  if (govMode == GovMode::GOV_HOLD) return last;
  return slewLimit(last, tgt, rampRate, rampRate, dtSec);
}

}  // namespace xr
