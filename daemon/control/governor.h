#pragma once
// governorApply(): the single function between every duty request and the
// PWM (docs/control.md "Governor"). Bounds first, then the slew by govMode.
#include <algorithm>
#include <cmath>

#include "control/slew.h"
#include "core/modes.h"

namespace xr {

struct GovernorLimits {
  double MinDuty = 0.0;
  double MaxDuty = 100.0;
  double DutyRampRate = 50.0;  // %/s, symmetric (GOV_NORMAL_SLEW)
};

// finalMin = max(rpmMinDuty, MinDuty): even GOV_BYPASS_SLEW respects the tach
// floor and the hard bounds; only the descent speed is unrestricted.
inline double governorApply(double lastApplied, double request, GovMode govMode, double rpmMinDuty,
                            double dtSec, const GovernorLimits& lim) {
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
      return std::clamp(slewLimit(last, requestClamped, lim.DutyRampRate, lim.DutyRampRate, dtSec), finalMin,
                        hardMax);
  }
}

// The shutdown special case (runShutdownPath): effective minimum 0, so the
// duty can go below MinDuty/rpmMinDuty; ramps toward `target` at `rampRate`
// (%/s) unless bypass, and never above MaxDuty.
double governorApplyShutdown(double lastApplied, double target, GovMode govMode, double rampRate,
                             double dtSec, double maxDuty);

}  // namespace xr
