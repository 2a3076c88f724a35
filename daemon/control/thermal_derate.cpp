#include "control/thermal_derate.h"

#include <algorithm>
#include <cmath>

#include "control/slew.h"

namespace xr {

namespace {
// The time base of TempPIDFilterAlpha (the DS18B20 task's nominal period).
constexpr double kFilterSecond = 1.0;
// Far above any alternator's heating or cooling rate (~0.1 degF/s at most).
constexpr double kMaxPlausibleSlopeFPerSec = 1.0;
}  // namespace

ThermalDerate::ThermalDerate() : tempPID_(0, 0, 0, Pid::REVERSE) {}

void ThermalDerate::reset() noexcept { *this = ThermalDerate(); }

double ThermalDerate::update(const ThermalInputs& in, const Params& p) noexcept {
  if (p.IgnoreTemperature) {
    // T0 disabled with T1-T3: no derate at all.
    thermalPenaltyAmps_ = 0.0;
    tempPID_.resetIntegratorTo(0.0);
    holding_ = false;
    return thermalPenaltyAmps_;
  }
  tempPID_.setTunings(p.TempPIDKp, p.TempPIDKi, p.TempPIDKd);
  tempPID_.setOutputLimits(0.0, std::max(1.0, p.MaxTableValue));
  tempPID_.setTrackingGain(p.PIDTrackingGain);
  // Regulate with a margin under the limit: T1 warns at the limit +
  // TempWarnExcess (2 degF by default), closer than the loop's own ripple.
  tempPID_.setpoint = p.TemperatureLimitF - p.TempRegulationMarginF;
  if (tempPID_.mode() != Pid::AUTOMATIC) tempPID_.setMode(Pid::AUTOMATIC);

  // Stale or implausible input: the PID halts and the penalty HOLDS its last
  // value (never zeroed); T5 cuts the field if it stays stale.
  holding_ = !in.tempValid || !std::isfinite(in.TempToUse);
  if (holding_) return thermalPenaltyAmps_;

  if (!primed_) {
    tempFiltered_ = in.TempToUse;
    lastSampleNs_ = in.now;
    primed_ = true;
  } else if (in.tempFresh) {
    // TempPIDFilterAlpha is the weight of one second: a sensor read twice as
    // often gets half the step per sample twice, the same smoothing in time.
    const double dt = std::max(0.0, toSec(in.now - lastSampleNs_));
    const double alpha = 1.0 - std::pow(1.0 - std::clamp(p.TempPIDFilterAlpha, 0.0, 1.0), dt / kFilterSecond);
    tempFiltered_ += alpha * (in.TempToUse - tempFiltered_);
    lastSampleNs_ = in.now;
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
      const double slope =
          span > 0 ? (thermalSlopeBuffer_[newest] - thermalSlopeBuffer_[oldest]) / span : 0.0;
      // An alternator cannot heat or cool this fast: such a slope is a sensor
      // glitch in the window, and the last plausible slope stands.
      if (std::fabs(slope) <= kMaxPlausibleSlopeFPerSec) thermalSlopeFPerSec_ = slope;
    }
    projectedTempF_ = tempFiltered_ + thermalSlopeFPerSec_ * p.ThermalLookaheadSec;
    // A falling projection must not hide a present temperature already
    // over the setpoint (cooling slope while still too hot).
    tempPID_.input = std::max(projectedTempF_, tempFiltered_);
    tempPID_.compute(dt);
    lastComputeNs_ = in.now;
    haveCompute_ = true;
  }

  // Implied-penalty anti-windup, gated on outerError > 0: while temperature
  // itself drives the loop the integrator must be left alone.
  const double outerError = (p.TemperatureLimitF - p.TempPIDMarginF) - tempFiltered_;
  if (in.impliedPenalty > thermalPenaltyAmps_ && outerError > 0.0) {
    const double trackTarget = std::max(0.0, in.impliedPenalty - p.TempPIDAntiWindupMarginA);
    // The specification calls tempPID.TrackAppliedOutput(trackTarget) here; what it
    // describes is parking the integrator, which is what we do (a
    // back-calculation on the output would wind the integrator far above the
    // implied penalty while the P term is strongly negative).
    tempPID_.trackIntegratorTo(trackTarget, in.dtSec);
  }

  thermalPenaltyAmps_ = slewLimit(thermalPenaltyAmps_, tempPID_.output, p.ThermalPenaltyRiseRate,
                                  p.ThermalPenaltyFallRate, in.dtSec);
  return thermalPenaltyAmps_;
}

}  // namespace xr
