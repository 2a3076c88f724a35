// SetpointSlew: the setpoint's rise and fall rates (docs/control.md "Slew
// Rates and Time Constants").
#include "control/setpoint_slew.h"

#include "control/slew.h"
#include "core/finite.h"

namespace xr {

double SetpointSlew::update(const SlewInputs& in, const Params& p) noexcept {
  setpointCommand_ = in.command;
  // StartupRiseRate until caught up, FastSetpointRiseRate x rise inside the
  // post-protection window (with voltage headroom), fall unlimited while a
  // fast-OV clamp is acting.
  fastRiseActive_ = haveProtectionCleared_ &&
                    in.now - protectionClearedAt_ < fromMs(p.FastSetpointRiseWindowMs) && finite(in.IBV) &&
                    in.IBV < in.ChargingVoltageTarget - p.FastSetpointRiseHeadroomV;
  double rise = p.SetpointRiseRate;
  if (inStartupRamp_)
    rise = p.StartupRiseRate;
  else if (fastRiseActive_)
    rise = p.SetpointRiseRate * p.FastSetpointRiseRate;
  // The BMS's cap is a limit, not a request: the setpoint meets it at once
  // (its own warning ramp is already smooth).
  const double fall = in.fallUnlimited ? 1e9 : p.SetpointFallRate;
  setpointLimited_ = slewLimit(setpointLimited_, setpointCommand_, rise, fall, in.dtSec);
  if (inStartupRamp_ && setpointLimited_ >= setpointCommand_ - 1e-9) inStartupRamp_ = false;
  return setpointLimited_;
}

}  // namespace xr
