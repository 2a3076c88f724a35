// ControlLaw, the AUTO command path (docs/control.md "Command path"): the
// parts in their order, each fed the values the earlier ones produced.
#include "control/control_law.h"

#include <algorithm>
#include <cmath>

#include "control/rpm_tables.h"
#include "core/finite.h"
#include "params/constants.h"
#include "params/derived.h"

namespace xr {

ControlLaw::ControlLaw(const Params& p) : targets_(p), inner_(p) {}

void ControlLaw::updateChargingStage(const ControlSensors& s, const Params& p, bool manualMode,
                                     EventBatch& ev) noexcept {
  TargetInputs ti;
  ti.now = s.now;
  ti.IBV = s.IBV;
  ti.Bcur = s.Bcur;
  ti.SOC_percent = s.SOC_percent;
  ti.socKnown = s.socKnown;
  ti.thermalPenaltyAmps = command_.thermal().thermalPenaltyAmps();
  ti.uTargetAmps = command_.uTargetAmps();
  ti.setpointCommand = slew_.setpointCommand();
  ti.fieldResting = rest_.resting();
  ti.manualMode = manualMode;
  ti.autoMode = sysMode_ == SysMode::SYS_MODE_AUTO;
  ti.bmsCvlV = bms_.cvlCeilingV();
  targets_.update(ti, p, ev);
}

double ControlLaw::computeUTarget(const ControlSensors& s, const Params& p) noexcept {
  inner_.setRpmFloor(getMinDutyForRPM(p, s.rpm));
  CommandInputs ci;
  ci.now = s.now;
  ci.dtSec = filters_.controlDt();
  ci.rpm = s.rpm;
  ci.IBV = s.IBV;
  ci.TempToUse = s.TempToUse;
  ci.tempStamp = s.tempStamp;
  ci.Bcur = s.Bcur;
  ci.pidSignal = filters_.pidSignal();
  ci.bmsBatteryCapA = bms_.batteryCapA();
  ci.batteryChargeCapA = s.batteryChargeCapA;
  ci.tuningMode = p.TuningMode;
  if (p.TuningMode) {
    ci.waveTarget = tuning_.waveTarget(s.now, p);
  } else if (tuning_.running()) {
    tuning_.reset();  // nothing to clear unless a run is in progress (score/commit need one)
  }
  ci.zeroHold = holdsZeroBatteryCurrent(p);
  return command_.update(ci, p);
}

void ControlLaw::updateGovMode(const ControlSensors& s, const Params& p, const FastOvVerdict& ov) noexcept {
  const bool majorOV = finite(s.IBV) && s.IBV > alternatorHardShutdownV(p) + k::HARD_SHUTDOWN_BYPASS_OFFSET_V;
  const bool overshoot =
      fastOv_.updateOvershootLatch(targets_.voltageControlActive(), s.IBV, targets_.ChargingVoltageTarget());
  const bool bypass =
      majorOV || s.sensorFailureBypass || overshoot || ov.forceBypassSlew || sysId_.systemIdRunning();
  inner_.setGovMode(bypass ? GovMode::GOV_BYPASS_SLEW : GovMode::GOV_NORMAL_SLEW);
}

double ControlLaw::finishAuto(const ControlSensors& s, const Params& p, const FastOvVerdict& ov,
                              EventBatch& ev) noexcept {
  applyFastOv(s, p, ov);
  if (sysId_.systemIdRunning()) return runSystemIdTick(s, p, ev);
  // CH1 not fresh: the protections above already acted on the state; the
  // PID and the duty hold until the next sample (<= one ADS cycle).
  if (!s.ch1Fresh) return inner_.lastAppliedDuty();
  const double dt = filters_.controlDt();
  if (rest_.resting()) return holdAtRest();

  const double Icv = slewSetpoint(s, p, dt);
  const double duty = runInnerLoop(s, p, dt);

  if (p.TuningMode) tuning_.score(slew_.setpointLimited(), filters_.measuredAmps(), dt);
  if (p.CVTuningMode && finite(s.IBV)) targets_.scoreCvTuning(s.IBV, dt, p);
  CeilingInputs ce;
  ce.zeroHold = holdsZeroBatteryCurrent(p);
  ce.fastOvCapA = ov.fastOvCurrentCap;
  ce.voltageControlActive = targets_.voltageControlActive();
  ce.Icv = Icv;
  ce.fullField = duty >= p.MaxDuty - kFullFieldDutyBand && filters_.input().primed();
  ce.measuredFiltered = filters_.input().value();
  command_.noteCeiling(ce, p);
  if (rest_.startDue(restInputs(s, p), p)) return holdAtRest();
  return duty;
}

// The fast over-voltage supervisors' verdict on this tick: their current cap,
// cv_I and setpoint actions, and what their clearing restarts.
void ControlLaw::applyFastOv(const ControlSensors& s, const Params& p, const FastOvVerdict& ov) noexcept {
  EpisodeInputs ei;
  ei.ov = ov;
  ei.bcurSlowPrimed = filters_.bcurSlow().primed();
  ei.bcurSlowA = filters_.bcurSlow().value();
  ei.Bcur = s.Bcur;
  ei.measuredAmps = filters_.measuredAmps();
  const EpisodeOutcome o = fastOv_.update(ei);
  if (o.cleared) onProtectionCleared(s.now);
  if (o.reseed && finite(o.reseedAtA))
    cv_.requestReseedAt(o.reseedAtA);
  else if (o.reseed)
    cv_.requestReseed();
  command_.applyFastOvCap(ov.fastOvCurrentCap);
  if (ov.cvIAction != CvIAction::None) cv_.setCvI(ov.cv_I);
  if (ov.zeroSetpointLimited) slew_.setLimited(0.0);
  updateGovMode(s, p, ov);
  // The field-on edge after a rest restarts the startup ramp.
  if (rest_.resting() && s.ch1Fresh && rest_.endDue(restInputs(s, p), p)) cv_.requestReseed();
}

// Plant-delay step test: setpoint machinery skipped, inner PID pinned.
double ControlLaw::runSystemIdTick(const ControlSensors& s, const Params& p, EventBatch& ev) noexcept {
  if (!s.ch1Fresh) return inner_.lastAppliedDuty();
  bool finished = false;
  sysIdDutyOut_ = sysId_.systemIdTick(s.now, filters_.measuredAmps(), p, finished);
  const double duty = inner_.governorStep(p, sysIdDutyOut_, GovMode::GOV_BYPASS_SLEW, filters_.controlDt());
  inner_.track(sysIdDutyOut_, duty);
  if (!finished) return duty;
  const SystemIdSnapshot& pre = sysId_.snapshot();
  // Legality: still running normally in AUTO with the same CV context.
  const bool legal = sysMode_ == SysMode::SYS_MODE_AUTO;
  if (legal && pre.voltageControlActive == targets_.voltageControlActive()) {
    slew_.setLimited(pre.setpointLimited);
    cv_.restore(pre.cv_I);
  }
  inner_.resumeAuto(p);
  const SystemIdResult& r = sysId_.result();
  ev.push(makeEvent(s.now, EventLevel::Info, EventCode::SystemIdDone, Reason::NONE, r.deadTimeMs,
                    r.riseTimeMs, r.valid ? 1 : 0));
  return duty;
}

// The outer loops' command (the voltage loop's current, or the current
// target) and its slew into setpointLimited; returns the voltage loop's Icv.
double ControlLaw::slewSetpoint(const ControlSensors& s, const Params& p, double dt) noexcept {
  const bool cv = targets_.voltageControlActive();
  const double target = targets_.ChargingVoltageTarget();
  CvLoopInputs ci;
  ci.now = s.now;
  ci.dtSec = dt;
  ci.voltageControlActive = cv;
  ci.ChargingVoltageTarget = target;
  ci.IBV = finite(s.IBV) ? s.IBV : target;
  ci.cvDSlope = filters_.ibvSlope();
  ci.g_pidI_filtered = filters_.pidFiltered().value();
  ci.uTargetAmps = command_.uTargetAmps();
  ci.uTargetRaw = command_.uTargetRaw();
  ci.fastOvClampActive = fastOv_.clampActive();
  const double Icv = cv_.update(ci, p);
  SlewInputs si;
  si.now = s.now;
  si.dtSec = dt;
  si.command = cv ? Icv : command_.uTargetAmps();
  si.IBV = s.IBV;
  si.ChargingVoltageTarget = target;
  si.fallUnlimited = fastOv_.clampActive() || command_.bmsCapActive();
  slew_.update(si, p);
  return Icv;
}

// The inner current PID and the governor: the applied duty.
double ControlLaw::runInnerLoop(const ControlSensors& s, const Params& p, double dt) noexcept {
  const double pidSig = filters_.pidSignal();
  InnerInputs ii;
  ii.now = s.now;
  ii.dtSec = dt;
  // MaintainMode chases Bcur = 0 (the specification), and never with more
  // alternator current than the RPM cap and the thermal derate allow
  // (I_cmd): a max-selector hands the loop to whichever is over its limit.
  ii.input = holdsZeroBatteryCurrent(p) ? std::max(s.Bcur, pidSig - command_.I_cmd()) : pidSig;
  ii.setpoint = slew_.setpointLimited();
  ii.pidSignal = pidSig;
  ii.bmsCapActive = command_.bmsCapActive();
  ii.bmsAltCap = command_.bmsAltCap();
  return inner_.update(ii, p);
}

bool ControlLaw::tuningActive(const Params& p) const noexcept {
  // A tuning run owns the field: it must neither start nor keep a rest.
  return p.TuningMode || p.CVTuningMode || sysId_.systemIdRunning();
}

RestInputs ControlLaw::restInputs(const ControlSensors& s, const Params& p) const noexcept {
  RestInputs r;
  r.now = s.now;
  r.tuningActive = tuningActive(p);
  r.voltageControlActive = targets_.voltageControlActive();
  r.ChargingVoltageTarget = targets_.ChargingVoltageTarget();
  r.IBV = s.IBV;
  r.rpmMinDuty = inner_.rpmMinDuty();
  r.dutyRequest = inner_.dutyRequest();
  r.setpointCommand = slew_.setpointCommand();
  return r;
}

double ControlLaw::holdAtRest() noexcept {
  // Everything waits at zero, so the field-on edge starts from the floor
  // with the startup ramp, and the CV integrator is seeded afresh then.
  inner_.rest();
  slew_.rest();
  cv_.requestReseed();
  return 0.0;
}

}  // namespace xr
