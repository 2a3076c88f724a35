// CurrentCommand: the current target and its caps, in the command path's
// order (docs/control.md "Command path").
#include "control/current_command.h"

#include <algorithm>

#include "control/rpm_tables.h"
#include "core/alternator_temperature.h"
#include "core/finite.h"

namespace xr {

double CurrentCommand::update(const CommandInputs& in, const Params& p) noexcept {
  I_cap_ = getCapCurrentForRPM(p, in.rpm, in.IBV);

  // T0 on its own cadence; the penalty holds on stale input.
  ThermalInputs ti;
  ti.now = in.now;
  ti.dtSec = in.dtSec;
  ti.TempToUse = in.TempToUse;
  ti.tempFresh = in.tempStamp != lastTempStamp_;
  lastTempStamp_ = in.tempStamp;
  ti.tempValid = temperatureFresh(in.TempToUse, in.tempStamp, in.now);
  ti.impliedPenalty = std::max(0.0, I_cap_ - nonThermalCeiling_);
  const double penalty = thermal_.update(ti, p);

  double I_cmd = std::clamp(I_cap_ - penalty, 0.0, p.MaxTableValue);
  I_cmd = std::min(I_cmd, p.MaximumAllowedBatteryAmps);
  // Warm-up ceiling (this project's, off by default): for WarmupCeilingSec
  // after the field turns on, the command is held under WarmupCeilingAmps so
  // a cold alternator and belt are not loaded at full current at once.
  warmupActive_ =
      p.WarmupCeilingAmps > 0.0 && fieldOnAt_ >= 0 && in.now - fieldOnAt_ < fromSec(p.WarmupCeilingSec);
  if (warmupActive_) I_cmd = std::min(I_cmd, p.WarmupCeilingAmps);
  // The BMS's CCL and the battery-temperature cap limit BATTERY current, so
  // house loads are still served: the alternator may give the load it
  // carries now (alternator less battery current) plus the cap. Without a
  // battery current the cap is on the alternator alone (docs/batteries.md
  // "Temperature rules").
  bmsAltCap_ = kNoCeiling;
  if (const double bcap = std::min(in.bmsBatteryCapA, in.batteryChargeCapA); bcap < kNoCeiling) {
    const double load = finite(in.Bcur) ? std::max(0.0, in.pidSignal - in.Bcur) : 0.0;
    bmsAltCap_ = std::max(0.0, load + bcap);
  }
  bmsCapActive_ = bmsAltCap_ < I_cmd;
  I_cmd = std::min(I_cmd, bmsAltCap_);
  I_cmd_ = I_cmd;

  double u = I_cmd;
  if (in.tuningMode) u = std::min(in.waveTarget, I_cmd);  // every cap still applies
  if (in.zeroHold) u = 0.0;                               // ceiling enforcer: Icv -> 0 (clamp [0, 0])
  uTargetRaw_ = u;
  return uTargetRaw_;
}

void CurrentCommand::applyFastOvCap(double capA) noexcept {
  uTargetAmps_ = std::max(0.0, std::min(uTargetRaw_, capA));
}

void CurrentCommand::noteCeiling(const CeilingInputs& in, const Params& p) noexcept {
  double c = std::min(p.MaxTableValue, p.MaximumAllowedBatteryAmps);
  if (warmupActive_) c = std::min(c, p.WarmupCeilingAmps);
  c = std::min(c, bmsAltCap_);
  if (in.zeroHold) c = 0.0;
  c = std::min(c, in.fastOvCapA);
  if (in.voltageControlActive) c = std::min(c, in.Icv);
  // An alternator at full field makes all it can; a penalty that leaves it
  // more than that has no effect yet. Counting it as implied parks the
  // integrator at the edge of effect (a 160 A cap on a machine making 140 A
  // hot gave the loop 20 A of dead travel, and the overshoot).
  if (in.fullField) c = std::min(c, in.measuredFiltered);
  nonThermalCeiling_ = c;
}

}  // namespace xr
