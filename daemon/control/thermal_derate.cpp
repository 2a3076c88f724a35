#include "control/thermal_derate.h"

#include <algorithm>
#include <cmath>

#include "control/slew.h"

namespace xr {

ThermalDerate::ThermalDerate() : tempPID_(0, 0, 0, Pid::REVERSE) {}

void ThermalDerate::reset() { *this = ThermalDerate(); }

double ThermalDerate::update(const ThermalInputs& in, const Params& p) {
  if (p.IgnoreTemperature) {
    // T0 disabled with T1-T3: no derate at all.
    thermalPenaltyAmps_ = 0.0;
    tempPID_.ResetIntegratorTo(0.0);
    holding_ = false;
    return thermalPenaltyAmps_;
  }
  // Configured once per Params (paramsChanged(), reset()) instead of every
  // tick, with the same result: the setters are idempotent for equal values,
  // nothing else writes the gains, limits or setpoint, and the re-clamp in
  // SetOutputLimits is a no-op between changes because every writer of
  // output / outputSum below (Compute, TrackIntegratorTo, ResetIntegratorTo,
  // SetMode) clamps to these same limits. AUTOMATIC, once set, stays.
  if (pidStale_) {
    tempPID_.SetTunings(p.TempPIDKp, p.TempPIDKi, p.TempPIDKd);
    tempPID_.SetOutputLimits(0.0, std::max(1.0, p.MaxTableValue));
    tempPID_.SetTrackingGain(p.PIDTrackingGain);
    tempPID_.setpoint = p.TemperatureLimitF;
    if (tempPID_.GetMode() != Pid::AUTOMATIC) tempPID_.SetMode(Pid::AUTOMATIC);
    pidStale_ = false;
  }

  // Stale or implausible input: the PID halts and the penalty HOLDS its last
  // value (never zeroed); T5 cuts the field if it stays stale.
  holding_ = !in.tempValid || !std::isfinite(in.TempToUse);
  if (holding_) return thermalPenaltyAmps_;

  if (in.tempFresh || !primed_) {
    tempFiltered_ =
        primed_ ? tempFiltered_ + p.TempPIDFilterAlpha * (in.TempToUse - tempFiltered_) : in.TempToUse;
    primed_ = true;
  }

  const TimeNs interval = fromMs(p.TempPIDIntervalMs);
  if (!haveCompute_ || in.now - lastComputeNs_ >= interval) {
    const double dt = haveCompute_ ? toSec(in.now - lastComputeNs_) : toSec(interval);
    // 13-slot slope ring buffer at the compute cadence (13 x 5 s ~ 65 s).
    thermalSlopeBuffer_[slopeHead_] = tempFiltered_;
    slopeStamps_[slopeHead_] = in.now;
    slopeHead_ = (slopeHead_ + 1) % k::THERMAL_SLOPE_BUF;
    slopeCount_ = std::min(slopeCount_ + 1, k::THERMAL_SLOPE_BUF);
    if (slopeCount_ >= 2) {
      const int newest = (slopeHead_ + k::THERMAL_SLOPE_BUF - 1) % k::THERMAL_SLOPE_BUF;
      const int oldest = (slopeHead_ + k::THERMAL_SLOPE_BUF - slopeCount_) % k::THERMAL_SLOPE_BUF;
      const double span = toSec(slopeStamps_[newest] - slopeStamps_[oldest]);
      thermalSlopeFPerSec_ =
          span > 0 ? (thermalSlopeBuffer_[newest] - thermalSlopeBuffer_[oldest]) / span : 0.0;
    }
    projectedTempF_ = tempFiltered_ + thermalSlopeFPerSec_ * p.ThermalLookaheadSec;
    tempPID_.input = projectedTempF_;
    tempPID_.Compute(dt);
    lastComputeNs_ = in.now;
    haveCompute_ = true;
  }

  // Implied-penalty anti-windup, gated on outerError > 0: while temperature
  // itself drives the loop the integrator must be left alone.
  const double outerError = (p.TemperatureLimitF - p.TempPIDMarginF) - tempFiltered_;
  if (in.impliedPenalty > thermalPenaltyAmps_ && outerError > 0.0) {
    const double trackTarget = std::max(0.0, in.impliedPenalty - p.TempPIDAntiWindupMarginA);
    // The seed calls tempPID.TrackAppliedOutput(trackTarget) here; what it
    // describes is parking the integrator, which is what we do (a
    // back-calculation on the output would wind the integrator far above the
    // implied penalty while the P term is strongly negative).
    tempPID_.TrackIntegratorTo(trackTarget, in.dtSec);
  }

  thermalPenaltyAmps_ = slew_limit_f(thermalPenaltyAmps_, tempPID_.output, p.ThermalPenaltyRiseRate,
                                     p.ThermalPenaltyFallRate, in.dtSec);
  return thermalPenaltyAmps_;
}

}  // namespace xr
