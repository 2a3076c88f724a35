#include "control/governor.h"

#include <algorithm>
#include <cmath>

#include "control/slew.h"

namespace xr {

double governor_apply(double lastApplied, double request, GovMode govMode, double rpmMinDuty, double dtSec,
                      const GovernorLimits& lim) {
  const double hardMax = std::clamp(lim.MaxDuty, 0.0, 100.0);
  const double finalMin = std::min(std::max(std::max(rpmMinDuty, lim.MinDuty), 0.0), hardMax);
  const double req = std::isfinite(request) ? request : finalMin;  // bad request: safest legal duty
  const double requestClamped = std::clamp(req, finalMin, hardMax);
  const double last = std::isfinite(lastApplied) ? lastApplied : 0.0;
  switch (govMode) {
    case GovMode::GOV_BYPASS_SLEW:
      return requestClamped;
    case GovMode::GOV_HOLD:
      return std::clamp(last, finalMin, hardMax);
    case GovMode::GOV_NORMAL_SLEW:
    default:
      // Bounds are enforced on the result too: coming up from 0 after field
      // turn-on the duty starts at the floor, never below it.
      return std::clamp(slew_limit_f(last, requestClamped, lim.DutyRampRate, lim.DutyRampRate, dtSec),
                        finalMin, hardMax);
  }
}

double governor_apply_shutdown(double lastApplied, double target, GovMode govMode, double rampRate,
                               double dtSec, double maxDuty) {
  const double hardMax = std::clamp(maxDuty, 0.0, 100.0);
  const double tgt = std::clamp(std::isfinite(target) ? target : 0.0, 0.0, hardMax);
  const double last = std::isfinite(lastApplied) ? std::clamp(lastApplied, 0.0, hardMax) : 0.0;
  if (govMode == GovMode::GOV_BYPASS_SLEW) return tgt;
  if (govMode == GovMode::GOV_HOLD) return last;
  return slew_limit_f(last, tgt, rampRate, rampRate, dtSec);
}

}  // namespace xr
