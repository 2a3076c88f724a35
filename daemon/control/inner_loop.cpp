// InnerLoop: the current PID and the governor (docs/control.md "Inner
// loop", "Governor").
#include "control/inner_loop.h"

#include <algorithm>

#include "control/governor.h"
#include "control/input_filters.h"

namespace xr {

InnerLoop::InnerLoop(const Params& p) : pid_(p.PidKp, p.PidKi, p.PidKd, Pid::DIRECT) {
  configure(p);
  pid_.setMode(Pid::MANUAL);
}

void InnerLoop::configure(const Params& p) noexcept {
  // Applied on every call: SetOutputLimits also re-clamps output / outputSum,
  // which the MANUAL, shutdown and SystemID paths write unclamped, and the
  // gains follow the Params of this tick.
  pid_.setOutputLimits(p.MinDuty, std::max(p.MinDuty + 1e-6, p.MaxDuty));
  pid_.setTunings(p.PidKp, p.PidKi, p.PidKd);
  pid_.setTrackingGain(p.PIDTrackingGain);
}

double InnerLoop::update(const InnerInputs& in, const Params& p) noexcept {
  configure(p);
  if (pid_.mode() != Pid::AUTOMATIC) pid_.setMode(Pid::AUTOMATIC);
  pid_.input = in.input;
  pid_.setpoint = in.setpoint;
  // Every PidSampleDivisor-th fresh CH1, over the real dt since the last compute.
  if (++pidSampleCounter_ >= std::max(1, p.PidSampleDivisor)) {
    pidSampleCounter_ = 0;
    const double pdt = lastPidCompute_ < 0 ? in.dtSec : toSec(in.now - lastPidCompute_);
    if (pid_.compute(std::min(pdt, InputFilters::kMaxControlDtSec))) lastPidCompute_ = in.now;
  }
  snapToBmsStep(in);
  dutyRequest_ = pid_.output;
  const double duty = governorStep(p, dutyRequest_, govMode_, in.dtSec);
  pid_.trackAppliedOutput(duty, in.dtSec);
  lastAppliedDuty_ = duty;
  return duty;
}

// A BMS cap that steps down (a lower CCL, or the house load switched off
// under a binding cap): the duty drops in proportion at once (alternator
// current is about proportional to duty at one speed) and the governor's
// slew is bypassed, so the battery current meets the new limit within the
// field's time constant, not the integrator's. The PID trims from there.
// Falling duty is the safe direction; a slow cap ramp (warnings) never snaps.
void InnerLoop::snapToBmsStep(const InnerInputs& in) noexcept {
  if (in.bmsCapActive && in.bmsAltCap < bmsAltCapPrev_ - kBmsSnapStepA && in.pidSignal > in.bmsAltCap &&
      in.pidSignal > kBmsSnapStepA) {
    const double scaled = lastAppliedDuty_ * in.bmsAltCap / in.pidSignal;
    if (scaled < pid_.output) {
      pid_.resetIntegratorTo(scaled);
      govMode_ = GovMode::GOV_BYPASS_SLEW;
    }
  }
  bmsAltCapPrev_ = in.bmsAltCap;
}

double InnerLoop::governorStep(const Params& p, double request, GovMode mode, double dtSec) const noexcept {
  GovernorLimits lim{p.MinDuty, p.MaxDuty, p.DutyRampRate};
  return governorApply(lastAppliedDuty_, request, mode, rpmMinDuty_, dtSec, lim);
}

void InnerLoop::applyOpenLoop(double request, double duty) noexcept {
  dutyRequest_ = request;
  lastAppliedDuty_ = duty;
  pid_.resetIntegratorTo(duty);
}

void InnerLoop::track(double request, double duty) noexcept {
  dutyRequest_ = request;
  lastAppliedDuty_ = duty;
  pid_.output = duty;
  pid_.resetIntegratorTo(duty);
}

void InnerLoop::rest() noexcept {
  lastAppliedDuty_ = 0.0;
  dutyRequest_ = 0.0;
  pid_.resetIntegratorTo(0.0);
}

void InnerLoop::cut() noexcept {
  lastAppliedDuty_ = 0.0;
  dutyRequest_ = 0.0;
  pid_.setMode(Pid::MANUAL);
  pid_.output = 0.0;
  pid_.resetIntegratorTo(0.0);
}

void InnerLoop::enterManual() noexcept {
  pid_.setMode(Pid::MANUAL);
  pid_.output = lastAppliedDuty_;
  pid_.resetIntegratorTo(lastAppliedDuty_);
}

void InnerLoop::enterAuto(const Params& p, double pidSignal) noexcept {
  govMode_ = GovMode::GOV_NORMAL_SLEW;
  configure(p);
  pid_.setMode(Pid::MANUAL);
  pid_.output = lastAppliedDuty_;
  pid_.resetIntegratorTo(lastAppliedDuty_);
  pid_.input = pidSignal;
  pid_.setMode(Pid::AUTOMATIC);  // integrator -> lastAppliedDuty
  pidSampleCounter_ = 0;
  lastPidCompute_ = -1;
}

void InnerLoop::resumeAuto(const Params& p) noexcept {
  configure(p);
  pid_.setMode(Pid::AUTOMATIC);  // re-seeded to lastAppliedDuty (bumpless)
}

}  // namespace xr
