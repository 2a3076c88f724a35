// ControlLaw outside the AUTO path: MANUAL, Limp Home, the shutdown
// sequencer's ownership of the duty, and the bumpless mode-entry wrappers
// (docs/control.md "Mode entry functions").
#include <algorithm>

#include "control/control_law.h"
#include "control/governor.h"
#include "control/rpm_tables.h"
#include "params/constants.h"

namespace xr {

double ControlLaw::runManual(const ControlSensors& s, const Params& p, double manualDuty) noexcept {
  inner_.setRpmFloor(getMinDutyForRPM(p, s.rpm));
  inner_.setGovMode(GovMode::GOV_NORMAL_SLEW);  // manual still respects the tach floor
  const double duty = inner_.governorStep(p, manualDuty, GovMode::GOV_NORMAL_SLEW, filters_.tickDt());
  inner_.applyOpenLoop(manualDuty, duty);  // AUTO re-entry is bumpless
  slew_.setLimited(std::max(0.0, filters_.pidFiltered().value()));
  command_.clearCeiling();
  return duty;
}

double ControlLaw::runLimpHome(const ControlSensors& s, const Params& p, EventBatch& ev) noexcept {
  inner_.setRpmFloor(getMinDutyForRPM(p, s.rpm));
  inner_.setGovMode(GovMode::GOV_NORMAL_SLEW);
  GovernorLimits lim{p.MinDuty, p.MaxDuty, p.DutyRampRate};
  const double duty =
      limp_.handleLimpHome(s.now, inner_.lastAppliedDuty(), inner_.rpmMinDuty(), filters_.tickDt(), lim, ev);
  inner_.applyOpenLoop(k::LIMP_HOME_DUTY, duty);
  return duty;
}

void ControlLaw::trackShutdown(double appliedDuty, const Params& p, double rpm) noexcept {
  inner_.setRpmFloor(getMinDutyForRPM(p, rpm));
  inner_.track(appliedDuty, appliedDuty);
  limp_.reset();
}

void ControlLaw::leaveAuto(TimeNs now) noexcept {
  if (sysMode_ == SysMode::SYS_MODE_AUTO) leftAutoAt_ = now;
  rest_.leave();
}

void ControlLaw::enterManualLike(SysMode m) noexcept {
  leaveAuto(filters_.lastTick());
  sysMode_ = m;
  inner_.enterManual();
  sysId_.abort();
}

void ControlLaw::enterSysOff() noexcept {
  enterManualLike(SysMode::SYS_MODE_OFF);
  inner_.setGovMode(GovMode::GOV_NORMAL_SLEW);
}

void ControlLaw::enterSysManual() noexcept {
  enterManualLike(SysMode::SYS_MODE_MANUAL);
  inner_.setGovMode(GovMode::GOV_NORMAL_SLEW);
}

void ControlLaw::enterSysFault() noexcept {
  enterManualLike(SysMode::SYS_MODE_FAULT);
}  // govMode left to caller

void ControlLaw::enterSysAuto(const ControlSensors& s, const Params& p) noexcept {
  sysMode_ = SysMode::SYS_MODE_AUTO;
  // The original firmware always restarts in BULK (updateChargingStage
  // fast-forwards); this one resumes ABSORPTION / FLOAT after a short
  // absence (auto-zero, a lockout, an engine restart), so a full bank is not
  // re-absorbed each time.
  targets_.resume(s.now, leftAutoAt_ < 0 ? -1 : s.now - leftAutoAt_, p);
  cv_.requestReseed();  // back from a protection event: seed cv_I afresh
  inner_.enterAuto(p, filters_.pidSignal());
  // The specification sets setpointLimited = max(0, getTargetAmps()); we
  // read that as the current actually flowing, so the PID sees no step and
  // the StartupRiseRate ramp takes it from there.
  const Ema& pid = filters_.pidFiltered();
  slew_.seed(std::max(0.0, pid.primed() ? pid.value() : 0.0));
  fastOv_.clearOvershootLatch();
}

void ControlLaw::applyImmediateCut() noexcept {
  // docs/control.md "Mode entry functions": PWM 0, PID reset, FAULT,
  // setpointLimited 0, SystemID aborted (GPIO4 and the phase are protection's).
  leaveAuto(filters_.lastTick());
  inner_.cut();
  sysMode_ = SysMode::SYS_MODE_FAULT;
  slew_.setLimited(0.0);
  slew_.restartRamp();
  sysId_.abort();
}

void ControlLaw::onFieldTurnOn(TimeNs now) noexcept {
  command_.onFieldTurnOn(now);
  slew_.restartRamp();
}

bool ControlLaw::startSystemId(TimeNs now, bool autoRunning) noexcept {
  SystemIdSnapshot pre;
  pre.autoRunning = autoRunning && sysMode_ == SysMode::SYS_MODE_AUTO;
  pre.setpointLimited = slew_.setpointLimited();
  pre.lastAppliedDuty = inner_.lastAppliedDuty();
  pre.cv_I = cv_.cv_I();
  pre.voltageControlActive = targets_.voltageControlActive();
  if (!sysId_.start(now, pre)) return false;
  inner_.pinManual();
  return true;
}

}  // namespace xr
