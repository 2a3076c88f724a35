#include "control/control_law.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "control/rpm_tables.h"
#include "control/slew.h"
#include "core/finite.h"
#include "params/constants.h"
#include "params/derived.h"

namespace xr {

namespace {
// A control dt longer than this is not integrated as-is: such a gap means the
// sensor stalled (current-stale protection acts on it); integrating it would
// kick every loop.
constexpr double kMaxControlDtSec = 0.25;
constexpr double kNoCeiling = 1e300;

}  // namespace

ControlLaw::ControlLaw(const Params& p) : currentPID_(p.PidKp, p.PidKi, p.PidKd, Pid::DIRECT) {
  derive(p);
  configurePid(p);
  currentPID_.SetMode(Pid::MANUAL);
  ChargingVoltageTarget_ = p.BulkVoltage;
}

void ControlLaw::derive(const Params& p) {
  d_.overrideNow = p.MaintainMode || p.TargetVoltageMode || p.CVTuningMode;
  d_.overrideTargets = d_.overrideNow || p.TuningMode;
  d_.pidOutMax = std::max(p.MinDuty + 1e-6, p.MaxDuty);
  d_.majorOvV = alternatorHardShutdownV(p) + k::HARD_SHUTDOWN_BYPASS_OFFSET_V;
  d_.baseCeilingA = std::min(p.MaxTableValue, p.MaximumAllowedBatteryAmps);
  d_.pidDivisor = std::max(1, p.PidSampleDivisor);
  pidTuningsStale_ = true;
  rpm_.valid = false;  // the tables may have changed
}

// Same search and interpolation as getMinDutyForRPM / capCurrentAt, done
// only when rpm differs from the last call (by its bits, so NaN and -0.0 are
// handled exactly) or the Params were replaced since.
[[gnu::always_inline]] inline const ControlLaw::RpmLookup& ControlLaw::rpmLookup(const Params& p,
                                                                                 double rpm) {
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(rpm);
  if (!rpm_.valid || bits != rpm_.rpmBits) {
    const RpmPosition at = locateRpm(p.rpmTableRPMPoints, rpm);
    rpm_.minDuty = rpmTableValue(activeMinDutyTable(p), at);
    rpm_.capTable = capTableValueAt(p, at);
    rpm_.rpmBits = bits;
    rpm_.valid = true;
  }
  return rpm_;
}

void ControlLaw::setParams(const Params& p) {
  derive(p);
  thermal_.paramsChanged();
}

[[gnu::always_inline]] inline void ControlLaw::configurePid(const Params& p) {
  // The limits are applied on every call: SetOutputLimits also re-clamps
  // output / outputSum, which the MANUAL, shutdown and SystemID paths write
  // unclamped. The gains only change with the Params; nothing else sets them
  // (setting them again with the same values is a no-op, so applying them
  // once per setParams gives the same Pid state bit for bit).
  currentPID_.SetOutputLimits(p.MinDuty, d_.pidOutMax);
  if (pidTuningsStale_) {
    currentPID_.SetTunings(p.PidKp, p.PidKi, p.PidKd);
    currentPID_.SetTrackingGain(p.PIDTrackingGain);
    pidTuningsStale_ = false;
  }
}

void ControlLaw::updateFilters(const ControlSensors& s, const Params& p) {
  tickDt_ = lastTick_ < 0 ? 0.0 : std::clamp(toSec(s.now - lastTick_), 0.0, kMaxControlDtSec);
  lastTick_ = s.now;
  if (s.ch1Fresh) {
    controlDt_ =
        lastControlTick_ < 0 ? 0.0 : std::clamp(toSec(s.now - lastControlTick_), 0.0, kMaxControlDtSec);
    lastControlTick_ = s.now;
    if (finite(s.MeasuredAmps)) {
      MeasuredAmps_ = s.MeasuredAmps;
      emaInput_.update(s.MeasuredAmps, controlDt_, p.InputFilterTC);
      emaPid_.update(s.MeasuredAmps, controlDt_, p.OutputPIDFilterTC);
      maPid_.update(s.MeasuredAmps, p.OutputPIDMA_N);
    }
  } else {
    controlDt_ = 0.0;
  }
  if (s.ibvFresh && finite(s.IBV)) {
    const double dt = lastFilterIbvNs_ < 0 ? 0.0 : toSec(s.now - lastFilterIbvNs_);
    emaIBV_.update(s.IBV, dt, p.VoltageFilterTC);
    lastFilterIbvNs_ = s.now;
  }
  pidSig_ =
      p.OutputPIDSigSrc == 2 ? MeasuredAmps_ : (p.OutputPIDSigSrc == 1 ? maPid_.value() : emaPid_.value());
}

void ControlLaw::updateChargingStage(const ControlSensors& s, const Params& p, bool manualMode,
                                     EventBatch& ev) {
  const bool overrideNow = d_.overrideNow;
  // The stage machine only advances while charging in AUTO (IDLE keeps its
  // re-bulk watch while the field is off); override modes and manual hold it.
  const bool running = sysMode_ == SysMode::SYS_MODE_AUTO || stages_.inIdleStage();
  StageInputs si;
  si.now = s.now;
  si.v = s.IBV;
  si.Bcur = s.Bcur;
  si.thermalPenaltyAmps = thermal_.thermalPenaltyAmps();
  si.uTargetAmps = uTargetAmps_;
  si.SOC_percent = s.SOC_percent;
  si.socValid = finite(s.SOC_percent) && s.socKnown;
  si.suppressed = overrideNow || manualMode || !running || !finite(s.IBV);
  const ChargeStage before = stages_.stage();
  stages_.updateChargingStage(si, p);
  // Leaving an override resumes from BULK (seed: TargetVoltageMode exit ->
  // enter_sys_auto()).
  if (overrideWasActive_ && !overrideNow) stages_.resetToBulk(s.now);
  overrideWasActive_ = overrideNow;
  if (stages_.stage() != before) {
    ev.push(makeEvent(s.now, EventLevel::Info, EventCode::StageChanged, Reason::NONE,
                      static_cast<double>(before), static_cast<double>(stages_.stage())));
  }

  voltageControlActive_ = stages_.voltageControlActive();
  ChargingVoltageTarget_ = stages_.ChargingVoltageTarget(p);
  // Bulk voltage ceiling (ours; the legacy seed's "voltage soft limiter (bulk
  // only)" recast as a setpoint ceiling, as that seed's cap chain asks). The
  // newer seed runs BULK as pure CC with the hold timer, so a small or
  // high-resistance bank can climb from BulkVoltage to the hard-shutdown trip
  // (Bulk + 0.3 V) before bulkVoltageHoldMs elapses and cycle through warning
  // ramps and lockouts forever, never charging (seen in the simulator with a
  // 40 Ah AGM bank at 50 A). Once IBV reaches BulkVoltage in BULK, the CV loop
  // engages at the bulk target (bumpless seed, Groups 1-3 armed) until IBV
  // falls BULK_V_BAND_EXIT below it; the stage machine is untouched.
  const bool overrideTargets = d_.overrideTargets;
  if (stages_.inBulkStage() && !overrideTargets && finite(s.IBV)) {
    if (!bulkVoltageLimitActive_ && s.IBV >= p.BulkVoltage)
      bulkVoltageLimitActive_ = true;
    else if (bulkVoltageLimitActive_ && s.IBV < p.BulkVoltage - k::BULK_V_BAND_EXIT)
      bulkVoltageLimitActive_ = false;
  } else {
    bulkVoltageLimitActive_ = false;
  }
  if (bulkVoltageLimitActive_) voltageControlActive_ = true;
  if (p.CVTuningMode) {
    ChargingVoltageTarget_ = cvTuning_.target(s.now, ChargingVoltageTarget_, p);
    voltageControlActive_ = true;
  } else if (cvTuning_.running()) {
    cvTuning_.reset();  // nothing to clear unless a run is in progress (score/commit need one)
  }
  if (p.TargetVoltageMode) {
    ChargingVoltageTarget_ = p.TargetVoltageSetpoint;
    voltageControlActive_ = true;
  }
  if (p.MaintainMode) {
    // CV runs at the bulk target so Groups 1/2 stay armed; the ceiling is 0.
    ChargingVoltageTarget_ = p.BulkVoltage;
    voltageControlActive_ = true;
  }
  if (p.TuningMode) voltageControlActive_ = false;  // characterise the inner loop alone
}

double ControlLaw::computeUTarget(const ControlSensors& s, const Params& p) {
  // getMinDutyForRPM + getCapCurrentForRPM, sharing one breakpoint search.
  const RpmLookup& at = rpmLookup(p, s.rpm);
  rpmMinDuty_ = at.minDuty;
  I_cap_ = capCurrentFromTable(p, at.capTable, s.IBV);

  // T0 on its own cadence; the penalty holds on stale input.
  ThermalInputs ti;
  ti.now = s.now;
  ti.dtSec = controlDt_;
  ti.TempToUse = s.TempToUse;
  ti.tempFresh = s.tempStamp != lastTempStamp_;
  lastTempStamp_ = s.tempStamp;
  ti.tempValid = s.tempStamp != 0 && finite(s.TempToUse) && s.TempToUse >= k::TEMP_VALID_MIN_F &&
                 s.TempToUse <= k::TEMP_VALID_MAX_F && (s.now - s.tempStamp) <= fromMs(k::TEMP_STALE_MS);
  ti.impliedPenalty = std::max(0.0, I_cap_ - nonThermalCeiling_);
  const double penalty = thermal_.update(ti, p);

  double I_cmd = std::clamp(I_cap_ - penalty, 0.0, p.MaxTableValue);
  I_cmd = std::min(I_cmd, p.MaximumAllowedBatteryAmps);
  // Warm-up ceiling (ours, off by default): for WarmupCeilingSec after the
  // field turns on, the command is held under WarmupCeilingAmps so a cold
  // alternator and belt are not loaded at full current at once.
  warmupActive_ =
      p.WarmupCeilingAmps > 0.0 && fieldOnAt_ >= 0 && s.now - fieldOnAt_ < fromSec(p.WarmupCeilingSec);
  if (warmupActive_) I_cmd = std::min(I_cmd, p.WarmupCeilingAmps);
  I_cmd_ = I_cmd;

  double u = I_cmd;
  if (p.TuningMode) {
    u = std::min(tuning_.waveTarget(s.now, p), I_cmd);  // every cap still applies
  } else if (tuning_.running()) {
    tuning_.reset();  // nothing to clear unless a run is in progress (score/commit need one)
  }
  if (p.MaintainMode) u = 0.0;  // ceiling enforcer: Icv -> 0 (clamp [0, 0])
  uTargetRaw_ = u;
  return uTargetRaw_;
}

[[gnu::always_inline]] inline void ControlLaw::updateGovMode(const ControlSensors& s, const FastOvApply& fa) {
  const bool majorOV = finite(s.IBV) && s.IBV > d_.majorOvV;
  // CV overshoot latch: set when fast-OV fires in CV, released once IBV is
  // back under target + 20 mV (hysteresis stops chatter as the field collapses).
  if (cvOvershootBypass_ && (!voltageControlActive_ || !finite(s.IBV) ||
                             s.IBV < ChargingVoltageTarget_ + k::CV_OVERSHOOT_RELEASE_V))
    cvOvershootBypass_ = false;
  if (voltageControlActive_ && fa.fastOvClampActive) cvOvershootBypass_ = true;
  const bool bypass =
      majorOV || fa.sensorFailureBypass || cvOvershootBypass_ || fa.forceBypassSlew || sysId_.sysIDRunning();
  govMode_ = bypass ? GovMode::GOV_BYPASS_SLEW : GovMode::GOV_NORMAL_SLEW;
}

[[gnu::always_inline]] inline double ControlLaw::governorStep(const Params& p, double request, GovMode mode,
                                                              double dt) {
  GovernorLimits lim{p.MinDuty, p.MaxDuty, p.DutyRampRate};
  return governor_apply(lastAppliedDuty_, request, mode, rpmMinDuty_, dt, lim);
}

double ControlLaw::finishAuto(const ControlSensors& s, const Params& p, const FastOvApply& fa,
                              EventBatch& ev) {
  fastOvClampActive_ = fa.fastOvClampActive;
  if (fastOvWasActive_ && !fastOvClampActive_) onProtectionCleared(s.now);
  fastOvWasActive_ = fastOvClampActive_;
  uTargetAmps_ = std::max(0.0, std::min(uTargetRaw_, fa.fastOvCurrentCap));
  if (fa.setCvI) cv_.setCvI(fa.cv_I);
  if (fa.zeroSetpointLimited) setpointLimited_ = 0.0;
  updateGovMode(s, fa);

  if (sysId_.sysIDRunning()) {
    // Plant-delay step test: setpoint machinery skipped, inner PID pinned.
    if (!s.ch1Fresh) return lastAppliedDuty_;
    bool finished = false;
    sysIdDutyOut_ = sysId_.systemID_tick(s.now, MeasuredAmps_, p, finished);
    const double duty = governorStep(p, sysIdDutyOut_, GovMode::GOV_BYPASS_SLEW, controlDt_);
    dutyRequest_ = sysIdDutyOut_;
    lastAppliedDuty_ = duty;
    currentPID_.output = duty;
    currentPID_.ResetIntegratorTo(duty);
    if (finished) {
      const SystemIdSnapshot& pre = sysId_.snapshot();
      // Legality: still running normally in AUTO with the same CV context.
      const bool legal = sysMode_ == SysMode::SYS_MODE_AUTO;
      if (legal && pre.voltageControlActive == voltageControlActive_) {
        setpointLimited_ = pre.setpointLimited;
        cv_.restore(pre.cv_I);
      }
      configurePid(p);
      currentPID_.SetMode(Pid::AUTOMATIC);  // re-seeded to lastAppliedDuty (bumpless)
      const SystemIdResult& r = sysId_.result();
      ev.push(makeEvent(s.now, EventLevel::Info, EventCode::SystemIdDone, Reason::NONE, r.deadTimeMs,
                        r.riseTimeMs, r.valid ? 1 : 0));
    }
    return duty;
  }

  // CH1 not fresh: the protections above already acted on the state; the
  // PID and the duty hold until the next sample (<= one ADS cycle).
  if (!s.ch1Fresh) return lastAppliedDuty_;
  const double dt = controlDt_;

  CvLoopInputs ci;
  ci.now = s.now;
  ci.dtSec = dt;
  ci.voltageControlActive = voltageControlActive_;
  ci.ChargingVoltageTarget = ChargingVoltageTarget_;
  ci.IBV = finite(s.IBV) ? s.IBV : ChargingVoltageTarget_;
  ci.filtV = emaIBV_.primed() ? emaIBV_.value() : ci.IBV;
  ci.g_pidI_filtered = emaPid_.value();
  ci.uTargetAmps = uTargetAmps_;
  ci.uTargetRaw = uTargetRaw_;
  ci.fastOvClampActive = fastOvClampActive_;
  const double Icv = cv_.update(ci, p);
  setpointCommand_ = voltageControlActive_ ? Icv : uTargetAmps_;

  // Setpoint slew: StartupRiseRate until caught up, FastSetpointRiseRate x
  // rise inside the post-protection window (with voltage headroom), fall
  // unlimited while a fast-OV clamp is acting.
  fastRiseActive_ = haveProtectionCleared_ &&
                    s.now - protectionClearedAt_ < fromMs(p.FastSetpointRiseWindowMs) && finite(s.IBV) &&
                    s.IBV < ChargingVoltageTarget_ - p.FastSetpointRiseHeadroomV;
  double rise = p.SetpointRiseRate;
  if (inStartupRamp_)
    rise = p.StartupRiseRate;
  else if (fastRiseActive_)
    rise = p.SetpointRiseRate * p.FastSetpointRiseRate;
  const double fall = fastOvClampActive_ ? 1e9 : p.SetpointFallRate;
  setpointLimited_ = slew_limit_f(setpointLimited_, setpointCommand_, rise, fall, dt);
  if (inStartupRamp_ && setpointLimited_ >= setpointCommand_ - 1e-9) inStartupRamp_ = false;

  // Inner current PID, every PidSampleDivisor-th fresh CH1, real dt.
  configurePid(p);
  if (currentPID_.GetMode() != Pid::AUTOMATIC) currentPID_.SetMode(Pid::AUTOMATIC);
  currentPID_.input = p.MaintainMode ? s.Bcur : pidSig_;
  currentPID_.setpoint = setpointLimited_;
  if (++pidSampleCounter_ >= d_.pidDivisor) {
    pidSampleCounter_ = 0;
    const double pdt = lastPidCompute_ < 0 ? dt : toSec(s.now - lastPidCompute_);
    if (currentPID_.Compute(std::min(pdt, kMaxControlDtSec))) lastPidCompute_ = s.now;
  }
  dutyRequest_ = currentPID_.output;

  const double duty = governorStep(p, dutyRequest_, govMode_, dt);
  currentPID_.TrackAppliedOutput(duty, dt);
  lastAppliedDuty_ = duty;

  if (p.TuningMode) tuning_.score(setpointLimited_, MeasuredAmps_, dt);
  if (p.CVTuningMode && finite(s.IBV)) cvTuning_.score(s.IBV, dt, p);

  // Non-thermal ceiling for T0's implied-penalty anti-windup (next tick).
  double c = d_.baseCeilingA;
  if (warmupActive_) c = std::min(c, p.WarmupCeilingAmps);
  if (p.MaintainMode) c = 0.0;
  c = std::min(c, fa.fastOvCurrentCap);
  if (voltageControlActive_) c = std::min(c, Icv);
  nonThermalCeiling_ = c;
  return duty;
}

double ControlLaw::runManual(const ControlSensors& s, const Params& p, double manualDuty) {
  rpmMinDuty_ = rpmLookup(p, s.rpm).minDuty;
  govMode_ = GovMode::GOV_NORMAL_SLEW;  // manual still respects the tach floor
  dutyRequest_ = manualDuty;
  const double duty = governorStep(p, manualDuty, govMode_, tickDt_);
  lastAppliedDuty_ = duty;
  currentPID_.ResetIntegratorTo(duty);  // AUTO re-entry is bumpless
  setpointLimited_ = std::max(0.0, emaPid_.value());
  nonThermalCeiling_ = kNoCeiling;
  return duty;
}

double ControlLaw::runLimpHome(const ControlSensors& s, const Params& p, EventBatch& ev) {
  rpmMinDuty_ = rpmLookup(p, s.rpm).minDuty;
  govMode_ = GovMode::GOV_NORMAL_SLEW;
  dutyRequest_ = k::LIMP_HOME_DUTY;
  GovernorLimits lim{p.MinDuty, p.MaxDuty, p.DutyRampRate};
  const double duty = limp_.handleLimpHome(s.now, lastAppliedDuty_, rpmMinDuty_, tickDt_, lim, ev);
  lastAppliedDuty_ = duty;
  currentPID_.ResetIntegratorTo(duty);
  return duty;
}

void ControlLaw::trackShutdown(double appliedDuty, const Params& p, double rpm) {
  rpmMinDuty_ = rpmLookup(p, rpm).minDuty;
  lastAppliedDuty_ = appliedDuty;
  dutyRequest_ = appliedDuty;
  currentPID_.output = appliedDuty;
  currentPID_.ResetIntegratorTo(appliedDuty);
  limp_.reset();
}

void ControlLaw::enterManualLike(SysMode m) {
  sysMode_ = m;
  currentPID_.SetMode(Pid::MANUAL);
  currentPID_.output = lastAppliedDuty_;
  currentPID_.ResetIntegratorTo(lastAppliedDuty_);
  sysId_.abort();
}

void ControlLaw::enter_sys_off() {
  enterManualLike(SysMode::SYS_MODE_OFF);
  govMode_ = GovMode::GOV_NORMAL_SLEW;
}

void ControlLaw::enter_sys_manual() {
  enterManualLike(SysMode::SYS_MODE_MANUAL);
  govMode_ = GovMode::GOV_NORMAL_SLEW;
}

void ControlLaw::enter_sys_fault() { enterManualLike(SysMode::SYS_MODE_FAULT); }  // govMode left to caller

void ControlLaw::enter_sys_auto(const ControlSensors& s, const Params& p) {
  sysMode_ = SysMode::SYS_MODE_AUTO;
  govMode_ = GovMode::GOV_NORMAL_SLEW;
  stages_.resetToBulk(s.now);  // always BULK; updateChargingStage fast-forwards
  configurePid(p);
  currentPID_.SetMode(Pid::MANUAL);
  currentPID_.output = lastAppliedDuty_;
  currentPID_.ResetIntegratorTo(lastAppliedDuty_);
  currentPID_.input = pidSig_;
  currentPID_.SetMode(Pid::AUTOMATIC);  // integrator -> lastAppliedDuty
  // The seed seeds setpointLimited = max(0, getTargetAmps()); we read that as
  // the current actually flowing, so the PID sees no step and the
  // StartupRiseRate ramp takes it from there.
  setpointLimited_ = std::max(0.0, emaPid_.primed() ? emaPid_.value() : 0.0);
  inStartupRamp_ = true;
  pidSampleCounter_ = 0;
  lastPidCompute_ = -1;
  cvOvershootBypass_ = false;
}

void ControlLaw::applyImmediateCut() {
  // field-control.md "Mode Entry Functions": PWM 0, PID reset, FAULT,
  // setpointLimited 0, SystemID aborted (GPIO4 and the phase are protection's).
  lastAppliedDuty_ = 0.0;
  dutyRequest_ = 0.0;
  sysMode_ = SysMode::SYS_MODE_FAULT;
  currentPID_.SetMode(Pid::MANUAL);
  currentPID_.output = 0.0;
  currentPID_.ResetIntegratorTo(0.0);
  setpointLimited_ = 0.0;
  inStartupRamp_ = true;
  sysId_.abort();
}

void ControlLaw::onFieldTurnOn(TimeNs now) {
  fieldOnAt_ = now;
  inStartupRamp_ = true;
}

bool ControlLaw::startSystemId(TimeNs now, bool autoRunning) {
  slowTelemetryStale_ = true;
  SystemIdSnapshot pre;
  pre.autoRunning = autoRunning && sysMode_ == SysMode::SYS_MODE_AUTO;
  pre.setpointLimited = setpointLimited_;
  pre.lastAppliedDuty = lastAppliedDuty_;
  pre.cv_I = cv_.cv_I();
  pre.voltageControlActive = voltageControlActive_;
  if (!sysId_.start(now, pre)) return false;
  currentPID_.SetMode(Pid::MANUAL);
  return true;
}

void ControlLaw::fillTelemetry(ControlTelemetry& t) const {
  fillLoopTelemetry(t);
  fillTuningTelemetry(t);
}

void ControlLaw::updateTelemetry(ControlTelemetry& t) {
  fillLoopTelemetry(t);
  const bool active = tuningActive();
  if (active || slowTelemetryStale_) fillTuningTelemetry(t);
  // Still active: the next tick rewrites them anyway; just stopped: this
  // tick wrote the final values.
  slowTelemetryStale_ = active;
}

[[gnu::always_inline]] inline void ControlLaw::fillLoopTelemetry(ControlTelemetry& t) const {
  t.sysMode = sysMode_;
  t.govMode = govMode_;
  t.I_cap = I_cap_;
  t.I_cmd = I_cmd_;
  t.uTargetRaw = uTargetRaw_;
  t.uTargetAmps = uTargetAmps_;
  t.setpointCommand = setpointCommand_;
  t.setpointLimited = setpointLimited_;
  t.pidInput = currentPID_.input;
  t.pidOutput = currentPID_.output;
  t.innerTermP = currentPID_.GetPterm();
  t.innerTermI = currentPID_.GetIterm();
  t.innerTermD = currentPID_.GetDterm();
  t.dutyRequest = dutyRequest_;
  t.lastAppliedDuty = lastAppliedDuty_;
  t.rpmMinDuty = rpmMinDuty_;
  t.voltageControlActive = voltageControlActive_;
  t.ChargingVoltageTarget = ChargingVoltageTarget_;
  t.voltageTargetSlewed = cv_.voltageTargetSlewed();
  t.cv_I = cv_.cv_I();
  t.Icv = cv_.Icv();
  t.cv_I_track = cv_.cv_I_track();
  t.cv_I_aw_cap = cv_.cv_I_aw_cap();
  t.g_awState = cv_.g_awState();
  t.cvDSlope = cv_.cvDSlope();
  t.g_voltLoopActualIntervalMs = cv_.g_voltLoopActualIntervalMs();
  t.tempFiltered = thermal_.tempFiltered();
  t.projectedTempF = thermal_.projectedTempF();
  t.thermalSlopeFPerSec = thermal_.thermalSlopeFPerSec();
  t.thermalPenaltyAmps = thermal_.thermalPenaltyAmps();
  t.thermalPenaltyAmps_d = thermal_.penaltyTarget();
  t.thermalHolding = thermal_.holding();
  t.MeasuredAmps = MeasuredAmps_;
  t.MeasuredAmps_filtered = emaInput_.value();
  t.g_pidI_filtered = emaPid_.value();
  t.g_pidMA_N = maPid_.value();
  t.IBV_filtered = emaIBV_.value();
  t.inStartupRamp = inStartupRamp_;
  t.fastRiseActive = fastRiseActive_;
  t.warmupActive = warmupActive_;
  t.bulkVoltageLimitActive = bulkVoltageLimitActive_;
  t.fastOvClampActive = fastOvClampActive_;
  t.cvOvershootBypass = cvOvershootBypass_;
  t.inBulkStage = stages_.inBulkStage();
  t.inAbsorptionStage = stages_.inAbsorptionStage();
  t.inFloatStage = stages_.inFloatStage();
  t.inIdleStage = stages_.inIdleStage();
  t.tailSuppressedByThermal = stages_.tailSuppressedByThermal();
  t.rebulkBlockedBySoc = stages_.rebulkBlockedBySoc();
}

void ControlLaw::fillTuningTelemetry(ControlTelemetry& t) const {
  t.tuningRunning = tuning_.running();
  t.tuningHighPhase = tuning_.highPhase();
  t.tuningScore = tuning_.currentScore();
  t.tuningLogCount = tuning_.logCount();
  t.cvTuningRunning = cvTuning_.running();
  t.cvTuningScore = cvTuning_.currentScore();
  t.cvTuningSettleSec = cvTuning_.lastSettleSec();
  t.cvTuningLogCount = cvTuning_.logCount();
  t.sysIDRunning = sysId_.sysIDRunning();
  t.sysIDDutyOut = sysIdDutyOut_;
  t.sysIDValid = sysId_.result().valid;
  t.sysIDDeadTimeMs = sysId_.result().deadTimeMs;
  t.sysIDRiseTimeMs = sysId_.result().riseTimeMs;
  t.sysIDSlopeAps = sysId_.result().slopeAps;
}

}  // namespace xr
