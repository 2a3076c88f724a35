// FieldRest: when a rest starts and when it ends (docs/deviations.md "Full
// bank at light load").
#include "control/field_rest.h"

#include "core/finite.h"

namespace xr {

bool FieldRest::startDue(const RestInputs& in, const Params& p) noexcept {
  // Nothing for the field to do: the duty is down at the RPM floor, or the
  // voltage loop asks for no current at all (a bank relaxing from absorption
  // sits above the float target by itself; the PID then parks the duty at the
  // alternator's knee, where it makes no current but keeps the field on).
  // A tuning run owns the field: it must neither start nor keep a rest.
  const bool atFloor = in.rpmMinDuty > 0.0 && in.dutyRequest <= in.rpmMinDuty;
  const bool noCurrentAsked = in.setpointCommand <= kRestNoCurrentA;
  const bool cond = !in.tuningActive && in.voltageControlActive && (atFloor || noCurrentAsked) &&
                    finite(in.IBV) && in.IBV > in.ChargingVoltageTarget + p.FieldRestMarginV;
  if (!cond) {
    armedAt_ = -1;
    return false;
  }
  if (armedAt_ < 0) armedAt_ = in.now;
  if (in.now - armedAt_ < fromMs(p.FieldRestDelayMs)) return false;
  armedAt_ = -1;
  resting_ = true;
  return true;
}

bool FieldRest::endDue(const RestInputs& in, const Params& p) noexcept {
  // The stage or an override changed what the loop holds, the voltage is
  // unknown, or the bank has come down under its target: the field works again.
  const bool over = !in.voltageControlActive || in.tuningActive || !finite(in.IBV) ||
                    in.IBV < in.ChargingVoltageTarget - p.FieldRestWakeV;
  if (over) resting_ = false;  // the field-on edge restarts the startup ramp
  return over;
}

}  // namespace xr
