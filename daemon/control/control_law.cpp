// ControlLaw, the AUTO command path (docs/control.md "Command path"):
// filters, uTarget, CV loop, setpoint slew, current PID and governor.
#include "control/control_law.h"

#include <algorithm>
#include <cmath>

#include "control/rpm_tables.h"
#include "control/slew.h"
#include "core/alternator_temperature.h"
#include "core/finite.h"
#include "params/constants.h"
#include "params/derived.h"

namespace xr {

ControlLaw::ControlLaw(const Params& p) : currentPID_(p.PidKp, p.PidKi, p.PidKd, Pid::DIRECT) {
  configurePid(p);
  currentPID_.setMode(Pid::MANUAL);
  ChargingVoltageTarget_ = p.BulkVoltage;
}

void ControlLaw::configurePid(const Params& p) noexcept {
  // Applied on every call: SetOutputLimits also re-clamps output / outputSum,
  // which the MANUAL, shutdown and SystemID paths write unclamped, and the
  // gains follow the Params of this tick.
  currentPID_.setOutputLimits(p.MinDuty, std::max(p.MinDuty + 1e-6, p.MaxDuty));
  currentPID_.setTunings(p.PidKp, p.PidKi, p.PidKd);
  currentPID_.setTrackingGain(p.PIDTrackingGain);
}

void ControlLaw::updateFilters(const ControlSensors& s, const Params& p) noexcept {
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
  if (finite(s.Bcur)) emaBcur_.update(s.Bcur, tickDt_, kBcurSlowTcMs);
  if (s.ibvFresh && finite(s.IBV)) {
    const double dt = lastFilterIbvNs_ < 0 ? 0.0 : toSec(s.now - lastFilterIbvNs_);
    emaIBV_.update(s.IBV, dt, p.VoltageFilterTC);
    // cvDSlope between fresh samples, over the time they are apart.
    if (dt > 0.0) ibvSlope_ = (emaIBV_.value() - lastFiltV_) / dt;
    lastFiltV_ = emaIBV_.value();
    lastFilterIbvNs_ = s.now;
  }
  pidSig_ =
      p.OutputPIDSigSrc == 2 ? MeasuredAmps_ : (p.OutputPIDSigSrc == 1 ? maPid_.value() : emaPid_.value());
}

double ControlLaw::computeUTarget(const ControlSensors& s, const Params& p) noexcept {
  rpmMinDuty_ = getMinDutyForRPM(p, s.rpm);
  I_cap_ = getCapCurrentForRPM(p, s.rpm, s.IBV);

  // T0 on its own cadence; the penalty holds on stale input.
  ThermalInputs ti;
  ti.now = s.now;
  ti.dtSec = controlDt_;
  ti.TempToUse = s.TempToUse;
  ti.tempFresh = s.tempStamp != lastTempStamp_;
  lastTempStamp_ = s.tempStamp;
  ti.tempValid = temperatureFresh(s.TempToUse, s.tempStamp, s.now);
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
  // The BMS's CCL and the battery-temperature cap limit BATTERY current, so
  // house loads are still served: the alternator may give the load it
  // carries now (alternator less battery current) plus the cap. Without a
  // battery current the cap is on the alternator alone (docs/batteries.md
  // "Temperature rules").
  bmsAltCap_ = kNoCeiling;
  if (const double bcap = std::min(bms_.batteryCapA(), s.batteryChargeCapA); bcap < kNoCeiling) {
    const double load = finite(s.Bcur) ? std::max(0.0, pidSig_ - s.Bcur) : 0.0;
    bmsAltCap_ = std::max(0.0, load + bcap);
  }
  bmsCapActive_ = bmsAltCap_ < I_cmd;
  I_cmd = std::min(I_cmd, bmsAltCap_);
  I_cmd_ = I_cmd;

  double u = I_cmd;
  if (p.TuningMode) {
    u = std::min(tuning_.waveTarget(s.now, p), I_cmd);  // every cap still applies
  } else if (tuning_.running()) {
    tuning_.reset();  // nothing to clear unless a run is in progress (score/commit need one)
  }
  if (holdsZeroBatteryCurrent(p)) u = 0.0;  // ceiling enforcer: Icv -> 0 (clamp [0, 0])
  uTargetRaw_ = u;
  return uTargetRaw_;
}

void ControlLaw::updateGovMode(const ControlSensors& s, const Params& p, const FastOvApply& fa) noexcept {
  const bool majorOV = finite(s.IBV) && s.IBV > alternatorHardShutdownV(p) + k::HARD_SHUTDOWN_BYPASS_OFFSET_V;
  // CV overshoot latch: set when fast-OV fires in CV, released once IBV is
  // back under target + 20 mV (hysteresis stops chatter as the field collapses).
  if (cvOvershootBypass_ && (!voltageControlActive_ || !finite(s.IBV) ||
                             s.IBV < ChargingVoltageTarget_ + k::CV_OVERSHOOT_RELEASE_V))
    cvOvershootBypass_ = false;
  if (voltageControlActive_ && fa.fastOvClampActive) cvOvershootBypass_ = true;
  const bool bypass = majorOV || fa.sensorFailureBypass || cvOvershootBypass_ || fa.forceBypassSlew ||
                      sysId_.systemIdRunning();
  govMode_ = bypass ? GovMode::GOV_BYPASS_SLEW : GovMode::GOV_NORMAL_SLEW;
}

void ControlLaw::reseedAfterLoadDump(const ControlSensors& s) noexcept {
  // The bank at its target accepted dumpAcceptA_ before the load went; what
  // is still drawn beside it is the alternator current less the battery's,
  // now. Their sum holds the target. The inner loop's filtered current
  // still carries the dumped load (~1 s behind): seeding from it drove the
  // bank back over the target and kept the field off while an AGM's charge
  // overpotential relaxed (an engine dropped to idle while cruising). Without a
  // battery current the original firmware's bumpless reseed stands.
  if (finite(dumpAcceptA_) && finite(s.Bcur) && finite(MeasuredAmps_)) {
    cv_.requestReseedAt(std::max(0.0, dumpAcceptA_ + (MeasuredAmps_ - s.Bcur)));
  } else {
    cv_.requestReseed();
  }
  dumpAcceptA_ = kNoValue;
}

double ControlLaw::governorStep(const Params& p, double request, GovMode mode, double dt) noexcept {
  GovernorLimits lim{p.MinDuty, p.MaxDuty, p.DutyRampRate};
  return governorApply(lastAppliedDuty_, request, mode, rpmMinDuty_, dt, lim);
}

double ControlLaw::finishAuto(const ControlSensors& s, const Params& p, const FastOvApply& fa,
                              EventBatch& ev) noexcept {
  applyFastOv(s, p, fa);
  if (sysId_.systemIdRunning()) return runSystemIdTick(s, p, ev);
  // CH1 not fresh: the protections above already acted on the state; the
  // PID and the duty hold until the next sample (<= one ADS cycle).
  if (!s.ch1Fresh) return lastAppliedDuty_;
  const double dt = controlDt_;
  if (fieldResting_) return holdAtRest();

  const double Icv = slewSetpoint(s, p, dt);
  runCurrentPid(s, p, dt);
  const double duty = governorStep(p, dutyRequest_, govMode_, dt);
  currentPID_.trackAppliedOutput(duty, dt);
  lastAppliedDuty_ = duty;

  if (p.TuningMode) tuning_.score(setpointLimited_, MeasuredAmps_, dt);
  if (p.CVTuningMode && finite(s.IBV)) cvTuning_.score(s.IBV, dt, p);
  nonThermalCeiling_ = nonThermalCeiling(p, fa, duty, Icv);
  if (restDue(s, p)) {
    fieldResting_ = true;
    return holdAtRest();
  }
  return duty;
}

// The fast over-voltage supervisors' verdict on this tick: their current cap,
// cv_I and setpoint actions, and what their clearing restarts.
void ControlLaw::applyFastOv(const ControlSensors& s, const Params& p, const FastOvApply& fa) noexcept {
  fastOvClampActive_ = fa.fastOvClampActive;
  fastOvCapA_ = fa.fastOvCurrentCap;
  if (fa.zeroSetpointLimited && !loadDumpInEpisode_)
    dumpAcceptA_ = emaBcur_.primed() ? emaBcur_.value() : kNoValue;
  if (fa.zeroSetpointLimited) loadDumpInEpisode_ = true;
  if (fastOvWasActive_ && !fastOvClampActive_) {
    onProtectionCleared(s.now);
    // Ours, after the original firmware: a load dump snapped cv_I to 0 and
    // bled its AW cap; reseed (cap cleared) so the recovery starts from the
    // current the bank needs now. Group 1/2/3 clamps keep the seed's slow
    // AW recovery: their current was too high, a reseed would restore it.
    if (loadDumpInEpisode_) reseedAfterLoadDump(s);
    loadDumpInEpisode_ = false;
  }
  fastOvWasActive_ = fastOvClampActive_;
  uTargetAmps_ = std::max(0.0, std::min(uTargetRaw_, fa.fastOvCurrentCap));
  if (fa.setCvI) cv_.setCvI(fa.cv_I);
  if (fa.zeroSetpointLimited) setpointLimited_ = 0.0;
  updateGovMode(s, p, fa);
  if (fieldResting_ && s.ch1Fresh && restOver(s, p)) {
    fieldResting_ = false;  // the field-on edge restarts the startup ramp
    cv_.requestReseed();
  }
}

// Plant-delay step test: setpoint machinery skipped, inner PID pinned.
double ControlLaw::runSystemIdTick(const ControlSensors& s, const Params& p, EventBatch& ev) noexcept {
  if (!s.ch1Fresh) return lastAppliedDuty_;
  bool finished = false;
  sysIdDutyOut_ = sysId_.systemIdTick(s.now, MeasuredAmps_, p, finished);
  const double duty = governorStep(p, sysIdDutyOut_, GovMode::GOV_BYPASS_SLEW, controlDt_);
  dutyRequest_ = sysIdDutyOut_;
  lastAppliedDuty_ = duty;
  currentPID_.output = duty;
  currentPID_.resetIntegratorTo(duty);
  if (!finished) return duty;
  const SystemIdSnapshot& pre = sysId_.snapshot();
  // Legality: still running normally in AUTO with the same CV context.
  const bool legal = sysMode_ == SysMode::SYS_MODE_AUTO;
  if (legal && pre.voltageControlActive == voltageControlActive_) {
    setpointLimited_ = pre.setpointLimited;
    cv_.restore(pre.cv_I);
  }
  configurePid(p);
  currentPID_.setMode(Pid::AUTOMATIC);  // re-seeded to lastAppliedDuty (bumpless)
  const SystemIdResult& r = sysId_.result();
  ev.push(makeEvent(s.now, EventLevel::Info, EventCode::SystemIdDone, Reason::NONE, r.deadTimeMs,
                    r.riseTimeMs, r.valid ? 1 : 0));
  return duty;
}

// The outer loops' command (the voltage loop's current, or the current
// target) and its slew into setpointLimited_; returns the voltage loop's Icv.
double ControlLaw::slewSetpoint(const ControlSensors& s, const Params& p, double dt) noexcept {
  CvLoopInputs ci;
  ci.now = s.now;
  ci.dtSec = dt;
  ci.voltageControlActive = voltageControlActive_;
  ci.ChargingVoltageTarget = ChargingVoltageTarget_;
  ci.IBV = finite(s.IBV) ? s.IBV : ChargingVoltageTarget_;
  ci.cvDSlope = ibvSlope_;
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
  // The BMS's cap is a limit, not a request: the setpoint meets it at once
  // (its own warning ramp is already smooth).
  const double fall = fastOvClampActive_ || bmsCapActive_ ? 1e9 : p.SetpointFallRate;
  setpointLimited_ = slewLimit(setpointLimited_, setpointCommand_, rise, fall, dt);
  if (inStartupRamp_ && setpointLimited_ >= setpointCommand_ - 1e-9) inStartupRamp_ = false;
  return Icv;
}

// Inner current PID, every PidSampleDivisor-th fresh CH1, real dt: sets dutyRequest_.
void ControlLaw::runCurrentPid(const ControlSensors& s, const Params& p, double dt) noexcept {
  configurePid(p);
  if (currentPID_.mode() != Pid::AUTOMATIC) currentPID_.setMode(Pid::AUTOMATIC);
  // MaintainMode chases Bcur = 0 (seed), and ours: never with more
  // alternator current than the RPM cap and the thermal derate allow
  // (I_cmd): a max-selector hands the loop to whichever is over its limit.
  currentPID_.input = holdsZeroBatteryCurrent(p) ? std::max(s.Bcur, pidSig_ - I_cmd_) : pidSig_;
  currentPID_.setpoint = setpointLimited_;
  if (++pidSampleCounter_ >= std::max(1, p.PidSampleDivisor)) {
    pidSampleCounter_ = 0;
    const double pdt = lastPidCompute_ < 0 ? dt : toSec(s.now - lastPidCompute_);
    if (currentPID_.compute(std::min(pdt, kMaxControlDtSec))) lastPidCompute_ = s.now;
  }
  // A BMS cap that steps down (a lower CCL, or the house load switched off
  // under a binding cap): the duty drops in proportion at once (alternator
  // current is about proportional to duty at one speed) and the governor's
  // slew is bypassed, so the battery current meets the new limit within the
  // field's time constant, not the integrator's. The PID trims from there.
  // Falling duty is the safe direction; a slow cap ramp (warnings) never snaps.
  if (bmsCapActive_ && bmsAltCap_ < bmsAltCapPrev_ - kBmsSnapStepA && pidSig_ > bmsAltCap_ &&
      pidSig_ > kBmsSnapStepA) {
    const double scaled = lastAppliedDuty_ * bmsAltCap_ / pidSig_;
    if (scaled < currentPID_.output) {
      currentPID_.resetIntegratorTo(scaled);
      govMode_ = GovMode::GOV_BYPASS_SLEW;
    }
  }
  bmsAltCapPrev_ = bmsAltCap_;
  dutyRequest_ = currentPID_.output;
}

// Non-thermal ceiling for T0's implied-penalty anti-windup (next tick).
double ControlLaw::nonThermalCeiling(const Params& p, const FastOvApply& fa, double duty,
                                     double Icv) const noexcept {
  double c = std::min(p.MaxTableValue, p.MaximumAllowedBatteryAmps);
  if (warmupActive_) c = std::min(c, p.WarmupCeilingAmps);
  c = std::min(c, bmsAltCap_);
  if (holdsZeroBatteryCurrent(p)) c = 0.0;
  c = std::min(c, fa.fastOvCurrentCap);
  if (voltageControlActive_) c = std::min(c, Icv);
  // Ours: an alternator at full field makes all it can; a penalty that
  // leaves it more than that has no effect yet. Counting it as implied
  // parks the integrator at the edge of effect (a 160 A cap on a machine
  // making 140 A hot gave the loop 20 A of dead travel, and the overshoot).
  if (duty >= p.MaxDuty - kFullFieldDutyBand && emaInput_.primed()) c = std::min(c, emaInput_.value());
  return c;
}

}  // namespace xr
