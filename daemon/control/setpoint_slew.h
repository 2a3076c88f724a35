#pragma once
// SetpointSlew: the outer loops' command (the voltage loop's Icv, or the
// current target) slewed into setpointLimited, the inner PID's setpoint
// (docs/control.md "Slew Rates and Time Constants"): StartupRiseRate until
// caught up after a field-on edge, FastSetpointRiseRate inside the window
// after a protection cleared, an unlimited fall under a fast-OV or BMS cap.
#include "core/inputs.h"
#include "params/params.h"

namespace xr {

// What the slew reads each fresh CH1 tick in AUTO.
struct SlewInputs {
  TimeNs now = 0;
  double dtSec = 0.0;
  double command = 0.0;  // setpointCommand: Icv in CV, uTargetAmps otherwise
  double IBV = kNoValue;
  double ChargingVoltageTarget = 0.0;
  bool fallUnlimited = false;  // a fast-OV clamp or a binding BMS cap
};

class SetpointSlew {
 public:
  // One fresh CH1 tick: returns setpointLimited.
  double update(const SlewInputs& in, const Params& p) noexcept;

  // A protection cleared: opens the FastSetpointRiseRate window.
  void onProtectionCleared(TimeNs now) noexcept {
    protectionClearedAt_ = now;
    haveProtectionCleared_ = true;
  }
  // A field-on edge or a cut: the next rise is the startup ramp.
  void restartRamp() noexcept { inStartupRamp_ = true; }
  // Entering AUTO: start from the current flowing, with the startup ramp.
  void seed(double setpointA) noexcept {
    setpointLimited_ = setpointA;
    inStartupRamp_ = true;
  }
  // Set by MANUAL (bumpless re-entry), a load dump (0), a SystemID restore.
  void setLimited(double setpointA) noexcept { setpointLimited_ = setpointA; }
  // The field rests: command and setpoint wait at zero.
  void rest() noexcept {
    setpointLimited_ = 0.0;
    setpointCommand_ = 0.0;
  }

  double setpointCommand() const noexcept { return setpointCommand_; }
  double setpointLimited() const noexcept { return setpointLimited_; }
  bool inStartupRamp() const noexcept { return inStartupRamp_; }
  bool fastRiseActive() const noexcept { return fastRiseActive_; }

 private:
  double setpointCommand_ = 0.0;        // the outer loops' command of the last fresh tick
  double setpointLimited_ = 0.0;        // the slewed setpoint the inner PID follows
  bool inStartupRamp_ = false;          // StartupRiseRate until the setpoint catches up
  TimeNs protectionClearedAt_ = 0;      // the last protection clearing (the fast-rise window)
  bool haveProtectionCleared_ = false;  // a protection has cleared since start
  bool fastRiseActive_ = false;         // the fast-rise window applies this tick
};

}  // namespace xr
