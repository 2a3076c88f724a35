#pragma once
// governor_apply(): the single function between every duty request and the
// PWM (field-control.md "Governor"). Bounds first, then the slew by govMode.
#include "core/modes.h"

namespace xr {

struct GovernorLimits {
  double MinDuty = 0.0;
  double MaxDuty = 100.0;
  double DutyRampRate = 50.0;  // %/s, symmetric (GOV_NORMAL_SLEW)
};

// finalMin = max(rpmMinDuty, MinDuty): even GOV_BYPASS_SLEW respects the tach
// floor and the hard bounds; only the descent speed is unrestricted.
double governor_apply(double lastApplied, double request, GovMode govMode, double rpmMinDuty, double dtSec,
                      const GovernorLimits& lim);

// The shutdown special case (runShutdownPath): effective minimum 0, so the
// duty can go below MinDuty/rpmMinDuty; ramps toward `target` at `rampRate`
// (%/s) unless bypass, and never above MaxDuty.
double governor_apply_shutdown(double lastApplied, double target, GovMode govMode, double rampRate,
                               double dtSec, double maxDuty);

}  // namespace xr
