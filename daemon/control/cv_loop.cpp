#include "control/cv_loop.h"

#include <algorithm>
#include <cmath>

#include "control/slew.h"
#include "params/constants.h"

namespace xr {

void VoltageCvLoop::reset() noexcept { *this = VoltageCvLoop{}; }

void VoltageCvLoop::setCvI(double v) noexcept {
  if (!std::isfinite(v)) return;
  cv_I_ = std::max(0.0, v);
  cv_I_track_ = cv_I_;
}

void VoltageCvLoop::restore(double v) noexcept { setCvI(v); }

// voltageTargetSlewed: rises only as fast as cv_I can support given
// uTargetAmps; falls instantly (memoryless min()).
double VoltageCvLoop::slewedTarget(const CvLoopInputs& in, const Params& p) const noexcept {
  double e_needed = p.VoltageKp > 0.0 ? (in.uTargetAmps - cv_I_) / p.VoltageKp : 1e9;
  e_needed = std::max(e_needed, k::CV_E_NEEDED_MIN_V);
  return std::min(in.ChargingVoltageTarget, in.IBV + e_needed);
}

void VoltageCvLoop::seedOnEntry(const CvLoopInputs& in, const Params& p) noexcept {
  // Bumpless: Icv == g_pidI_filtered immediately, so setpointCommand continues
  // from wherever the current was.
  voltageTargetSlewed_ = slewedTarget(in, p);
  const double e = voltageTargetSlewed_ - in.IBV;
  const double base = reseedAmps_ >= 0.0 ? reseedAmps_ : in.g_pidI_filtered;
  reseedAmps_ = -1.0;
  const double start = clampd(base - p.VoltageKp * e, 0.0, std::max(0.0, in.uTargetAmps));
  cv_I_ = start;
  cv_I_track_ = start;
  cv_I_aw_cap_ = p.MaxTableValue;  // clear any stale post-event cap
  awSeedProtectStartNs_ = in.now;
  e_ = e;
  Icv_ = clampd(p.VoltageKp * e + cv_I_, 0.0, std::max(0.0, in.uTargetAmps));
  lastVoltageLoopNs_ = in.now;  // the entering edge is this tick's fire (no integration, dt = 0)
}

void VoltageCvLoop::fire(const CvLoopInputs& in, const Params& p, double dtSec) noexcept {
  voltageTargetSlewed_ = slewedTarget(in, p);
  const double e = voltageTargetSlewed_ - in.IBV;
  e_ = e;
  const double uT = std::max(0.0, in.uTargetAmps);
  const double KiDown = k::KI_DOWN_MULTIPLIER * p.VoltageKi;
  const double dI = (e >= 0.0 ? p.VoltageKi : KiDown) * e * dtSec;

  const double icvRaw = p.VoltageKp * e + cv_I_;
  const bool satHi = icvRaw >= uT;
  const bool satLo = icvRaw <= 0.0;
  const bool supervisorLimiting = in.fastOvClampActive && (in.uTargetAmps < in.uTargetRaw - 0.01);
  if (supervisorLimiting && dI > 0.0) {
    g_awState_ = 1;  // fast-OV supervisor limiting: freeze upward integration
  } else if ((satHi && dI > 0.0) || (satLo && dI < 0.0)) {
    g_awState_ = 2;  // standard saturation: freeze in the offending direction
  } else {
    cv_I_ += dI;
    if (!in.fastOvClampActive) g_awState_ = 0;
  }

  // Slope-aware bleed: active only near target (proxGain) so a depleted bank
  // charging fast is never starved.
  if (cvDSlope_ > p.SlopeBleedThresh) {
    const double proxGain = clampd(1.0 - e / p.SlopeBleedProxV, 0.0, 1.0);
    cv_I_ -= p.SlopeBleedK * (cvDSlope_ - p.SlopeBleedThresh) * dtSec * proxGain;
  }
  cv_I_ = clampd(cv_I_, 0.0, std::min(uT, std::max(0.0, cv_I_aw_cap_)));
  Icv_ = clampd(p.VoltageKp * e + cv_I_, 0.0, uT);
}

double VoltageCvLoop::update(const CvLoopInputs& in, const Params& p) noexcept {
  const double dt = in.dtSec > 0.0 ? in.dtSec : 0.0;
  if (cv_I_aw_cap_ < 0.0) cv_I_aw_cap_ = p.MaxTableValue;
  const double uT = std::max(0.0, in.uTargetAmps);

  // cvDSlope comes from the caller, taken between fresh IBV samples (this project's:
  // the specification's per-tick difference of a value that changes every ~4.5 ms
  // alternates between 0 and twice the slope).
  cvDSlope_ = std::isfinite(in.cvDSlope) ? in.cvDSlope : 0.0;

  const bool entering = in.voltageControlActive && (!wasActive_ || reseedPending_);
  wasActive_ = in.voltageControlActive;
  if (!in.voltageControlActive || entering) reseedPending_ = false;
  if (!in.voltageControlActive) reseedAmps_ = -1.0;
  if (entering) seedOnEntry(in, p);
  const bool seedProtect =
      awSeedProtectStartNs_ >= 0 && (in.now - awSeedProtectStartNs_) < fromMs(p.AwSeedProtectMs);

  // cv_I_aw_cap: bleeds during fast-OV, recovers slowly afterward (both scaled
  // by MaxTableValue so the aggression is the same for any alternator size).
  const double awBleedAmpS = p.AwBleedRate * p.MaxTableValue;
  const double awRecoverAmpS = p.AwRecoverRate * p.MaxTableValue;
  if (in.fastOvClampActive) {
    cv_I_aw_cap_ = std::max(0.0, cv_I_aw_cap_ - awBleedAmpS * dt);
  } else {
    cv_I_aw_cap_ = std::min(p.MaxTableValue, cv_I_aw_cap_ + awRecoverAmpS * dt);
  }

  if (!in.voltageControlActive) {
    // Tracker (Kt = 2/s): keep cv_I where it would need to be if CV engaged now.
    voltageTargetSlewed_ = in.ChargingVoltageTarget;
    const double e_bt = in.ChargingVoltageTarget - in.IBV;
    e_ = e_bt;
    if (!seedProtect) {
      const double cv_I_target = clampd(in.g_pidI_filtered - p.VoltageKp * e_bt, 0.0, uT);
      cv_I_track_ += std::min(1.0, k::CV_TRACKER_KT * dt) * (cv_I_target - cv_I_track_);
      cv_I_ = cv_I_track_;
    }
    g_awState_ = 4;
    Icv_ = clampd(p.VoltageKp * e_bt + cv_I_, 0.0, uT);
    lastVoltageLoopNs_ = 0;
    return Icv_;
  }

  // Per-tick bleed during fast-OV (state 3): the 100 ms loop is too slow to
  // counter an event that fires at control-tick cadence.
  if (in.fastOvClampActive && !seedProtect) {
    cv_I_ = std::max(0.0, cv_I_ - awBleedAmpS * dt);
    g_awState_ = 3;
  }
  cv_I_ = std::min(cv_I_, std::max(0.0, cv_I_aw_cap_));

  const TimeNs interval = fromMs(p.VoltageLoopInterval);
  if (!entering && in.now - lastVoltageLoopNs_ >= interval) {
    const double actual = toSec(in.now - lastVoltageLoopNs_);
    g_voltLoopActualIntervalMs_ = actual * 1e3;
    // This project's: a gap (the loop did not run) is not integrated as one long step;
    // at most two intervals' worth (30 s of OnOff = 0 moved cv_I 9 -> 33 A).
    fire(in, p, std::min(actual, 2.0 * toSec(interval)));
    lastVoltageLoopNs_ = in.now;
  }
  // The ceiling can fall between fires (fast-OV cap): honour it every tick.
  Icv_ = clampd(Icv_, 0.0, uT);
  return Icv_;
}

}  // namespace xr
