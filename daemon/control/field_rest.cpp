// Field rest (ours; docs/deviations.md "Full bank at light load"). The RPM
// duty floor (rpmMinDutyTable, for the tach signal) can push more current
// than a full bank at light load takes: the voltage then climbs past the
// target into the over-voltage protections. When the voltage loop asks for
// less than the floor, or for no current at all, and the bank still sits
// above its target, the field rests (enable LOW, duty 0) until the voltage
// falls back under the target.
#include <algorithm>

#include "control/control_law.h"
#include "core/finite.h"

namespace xr {

bool ControlLaw::tuningActive(const Params& p) const noexcept {
  // A tuning run owns the field: it must neither start nor keep a rest.
  return p.TuningMode || p.CVTuningMode || sysId_.systemIdRunning();
}

bool ControlLaw::restDue(const ControlSensors& s, const Params& p) noexcept {
  // Nothing for the field to do: the duty is down at the RPM floor, or the
  // voltage loop asks for no current at all (a bank relaxing from absorption
  // sits above the float target by itself; the PID then parks the duty at the
  // alternator's knee, where it makes no current but keeps the field on).
  const bool atFloor = rpmMinDuty_ > 0.0 && dutyRequest_ <= rpmMinDuty_;
  const bool noCurrentAsked = setpointCommand_ <= kRestNoCurrentA;
  const bool cond = !tuningActive(p) && voltageControlActive_ && (atFloor || noCurrentAsked) &&
                    finite(s.IBV) && s.IBV > ChargingVoltageTarget_ + p.FieldRestMarginV;
  if (!cond) {
    restArmedAt_ = -1;
    return false;
  }
  if (restArmedAt_ < 0) restArmedAt_ = s.now;
  if (s.now - restArmedAt_ < fromMs(p.FieldRestDelayMs)) return false;
  restArmedAt_ = -1;
  return true;
}

bool ControlLaw::restOver(const ControlSensors& s, const Params& p) const noexcept {
  // The stage or an override changed what the loop holds, the voltage is
  // unknown, or the bank has come down under its target: the field works again.
  return !voltageControlActive_ || tuningActive(p) || !finite(s.IBV) ||
         s.IBV < ChargingVoltageTarget_ - p.FieldRestWakeV;
}

double ControlLaw::holdAtRest() noexcept {
  // Everything waits at zero, so the field-on edge starts from the floor
  // with the startup ramp, and the CV integrator is seeded afresh then.
  lastAppliedDuty_ = 0.0;
  dutyRequest_ = 0.0;
  setpointLimited_ = 0.0;
  setpointCommand_ = 0.0;
  currentPID_.resetIntegratorTo(0.0);
  cv_.requestReseed();
  return 0.0;
}

}  // namespace xr
