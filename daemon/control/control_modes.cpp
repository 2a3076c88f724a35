// ControlLaw outside the AUTO path: MANUAL, Limp Home, the shutdown
// sequencer's ownership of the duty, and the bumpless mode-entry wrappers
// (docs/control.md "Mode entry functions").
#include <algorithm>

#include "control/control_law.h"
#include "control/rpm_tables.h"
#include "params/constants.h"

namespace xr {

double ControlLaw::runManual(const ControlSensors& s, const Params& p, double manualDuty) noexcept {
  rpmMinDuty_ = getMinDutyForRPM(p, s.rpm);
  govMode_ = GovMode::GOV_NORMAL_SLEW;  // manual still respects the tach floor
  dutyRequest_ = manualDuty;
  const double duty = governorStep(p, manualDuty, govMode_, tickDt_);
  lastAppliedDuty_ = duty;
  currentPID_.resetIntegratorTo(duty);  // AUTO re-entry is bumpless
  setpointLimited_ = std::max(0.0, emaPid_.value());
  nonThermalCeiling_ = kNoCeiling;
  return duty;
}

double ControlLaw::runLimpHome(const ControlSensors& s, const Params& p, EventBatch& ev) noexcept {
  rpmMinDuty_ = getMinDutyForRPM(p, s.rpm);
  govMode_ = GovMode::GOV_NORMAL_SLEW;
  dutyRequest_ = k::LIMP_HOME_DUTY;
  GovernorLimits lim{p.MinDuty, p.MaxDuty, p.DutyRampRate};
  const double duty = limp_.handleLimpHome(s.now, lastAppliedDuty_, rpmMinDuty_, tickDt_, lim, ev);
  lastAppliedDuty_ = duty;
  currentPID_.resetIntegratorTo(duty);
  return duty;
}

void ControlLaw::trackShutdown(double appliedDuty, const Params& p, double rpm) noexcept {
  rpmMinDuty_ = getMinDutyForRPM(p, rpm);
  lastAppliedDuty_ = appliedDuty;
  dutyRequest_ = appliedDuty;
  currentPID_.output = appliedDuty;
  currentPID_.resetIntegratorTo(appliedDuty);
  limp_.reset();
}

void ControlLaw::leaveAuto(TimeNs now) noexcept {
  if (sysMode_ == SysMode::SYS_MODE_AUTO) leftAutoAt_ = now;
  fieldResting_ = false;
  restArmedAt_ = -1;
}

void ControlLaw::enterManualLike(SysMode m) noexcept {
  leaveAuto(lastTick_);
  sysMode_ = m;
  currentPID_.setMode(Pid::MANUAL);
  currentPID_.output = lastAppliedDuty_;
  currentPID_.resetIntegratorTo(lastAppliedDuty_);
  sysId_.abort();
}

void ControlLaw::enterSysOff() noexcept {
  enterManualLike(SysMode::SYS_MODE_OFF);
  govMode_ = GovMode::GOV_NORMAL_SLEW;
}

void ControlLaw::enterSysManual() noexcept {
  enterManualLike(SysMode::SYS_MODE_MANUAL);
  govMode_ = GovMode::GOV_NORMAL_SLEW;
}

void ControlLaw::enterSysFault() noexcept {
  enterManualLike(SysMode::SYS_MODE_FAULT);
}  // govMode left to caller

void ControlLaw::enterSysAuto(const ControlSensors& s, const Params& p) noexcept {
  sysMode_ = SysMode::SYS_MODE_AUTO;
  govMode_ = GovMode::GOV_NORMAL_SLEW;
  // The seed always restarts in BULK (updateChargingStage fast-forwards);
  // ours resumes ABSORPTION / FLOAT after a short absence (auto-zero, a
  // lockout, an engine restart), so a full bank is not re-absorbed each time.
  stages_.resumeOrBulk(s.now, leftAutoAt_ < 0 ? -1 : s.now - leftAutoAt_, p);
  cv_.requestReseed();  // back from a protection event: seed cv_I afresh
  configurePid(p);
  currentPID_.setMode(Pid::MANUAL);
  currentPID_.output = lastAppliedDuty_;
  currentPID_.resetIntegratorTo(lastAppliedDuty_);
  currentPID_.input = pidSig_;
  currentPID_.setMode(Pid::AUTOMATIC);  // integrator -> lastAppliedDuty
  // The seed seeds setpointLimited = max(0, getTargetAmps()); we read that as
  // the current actually flowing, so the PID sees no step and the
  // StartupRiseRate ramp takes it from there.
  setpointLimited_ = std::max(0.0, emaPid_.primed() ? emaPid_.value() : 0.0);
  inStartupRamp_ = true;
  pidSampleCounter_ = 0;
  lastPidCompute_ = -1;
  cvOvershootBypass_ = false;
}

void ControlLaw::applyImmediateCut() noexcept {
  // docs/control.md "Mode entry functions": PWM 0, PID reset, FAULT,
  // setpointLimited 0, SystemID aborted (GPIO4 and the phase are protection's).
  leaveAuto(lastTick_);
  lastAppliedDuty_ = 0.0;
  dutyRequest_ = 0.0;
  sysMode_ = SysMode::SYS_MODE_FAULT;
  currentPID_.setMode(Pid::MANUAL);
  currentPID_.output = 0.0;
  currentPID_.resetIntegratorTo(0.0);
  setpointLimited_ = 0.0;
  inStartupRamp_ = true;
  sysId_.abort();
}

void ControlLaw::onFieldTurnOn(TimeNs now) noexcept {
  fieldOnAt_ = now;
  inStartupRamp_ = true;
}

bool ControlLaw::startSystemId(TimeNs now, bool autoRunning) noexcept {
  SystemIdSnapshot pre;
  pre.autoRunning = autoRunning && sysMode_ == SysMode::SYS_MODE_AUTO;
  pre.setpointLimited = setpointLimited_;
  pre.lastAppliedDuty = lastAppliedDuty_;
  pre.cv_I = cv_.cv_I();
  pre.voltageControlActive = voltageControlActive_;
  if (!sysId_.start(now, pre)) return false;
  currentPID_.setMode(Pid::MANUAL);
  return true;
}

}  // namespace xr
