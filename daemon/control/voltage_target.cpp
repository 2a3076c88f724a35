// VoltageTarget: the stage machine's step and the voltage target /
// voltageControlActive of this tick, override modes included (docs/control.md
// "Charging stages", "Override modes").
#include "control/voltage_target.h"

#include <algorithm>
#include <cmath>

#include "core/finite.h"
#include "params/constants.h"
#include "params/derived.h"

namespace xr {

void VoltageTarget::update(const TargetInputs& in, const Params& p, EventBatch& ev) noexcept {
  const bool overrideNow = p.MaintainMode || p.TargetVoltageMode || p.CVTuningMode;
  // The stage machine only advances while charging in AUTO (IDLE keeps its
  // re-bulk watch while the field is off); override modes and manual hold it.
  const bool running = in.autoMode || stages_.inIdleStage();
  StageInputs si;
  si.now = in.now;
  si.v = in.IBV;
  si.Bcur = in.Bcur;
  si.thermalPenaltyAmps = in.thermalPenaltyAmps;
  si.uTargetAmps = in.uTargetAmps;
  si.SOC_percent = in.SOC_percent;
  si.socValid = finite(in.SOC_percent) && in.socKnown;
  // The tail counts only while the voltage loop holds the absorption target
  // (last tick's loop state): a bank discharging into a load the alternator
  // cannot carry is below its target with the CV loop at its ceiling.
  si.voltageHeld = finite(in.IBV) && in.IBV >= p.AbsorptionVoltage - k::TAIL_HOLD_BAND_V &&
                   (in.fieldResting || in.setpointCommand < in.uTargetAmps - kTailHeadroomA);
  si.suppressed = overrideNow || in.manualMode || !running || !finite(in.IBV);
  const ChargeStage before = stages_.stage();
  stages_.updateChargingStage(si, p);
  // Leaving an override: the original firmware restarts in BULK
  // (TargetVoltageMode exit -> enterSysAuto()); this one resumes the stage
  // after a short one.
  if (overrideNow && !overrideWasActive_) overrideSince_ = in.now;
  if (overrideWasActive_ && !overrideNow) stages_.resumeOrBulk(in.now, in.now - overrideSince_, p);
  overrideWasActive_ = overrideNow;
  if (stages_.stage() != before) {
    ev.push(makeEvent(in.now, EventLevel::Info, EventCode::StageChanged, Reason::NONE,
                      static_cast<double>(before), static_cast<double>(stages_.stage())));
  }

  voltageControlActive_ = stages_.voltageControlActive();
  ChargingVoltageTarget_ = stages_.ChargingVoltageTarget(p);
  applyOverrides(in, p, overrideNow);
}

// The voltage target and whether the voltage loop runs, after the stage's:
// the bulk ceiling, the override modes, the idle hold and the BMS's CVL.
void VoltageTarget::applyOverrides(const TargetInputs& in, const Params& p, bool overrideNow) noexcept {
  // Bulk voltage ceiling (this project's; the legacy specification's
  // "voltage soft limiter (bulk only)" recast as a setpoint ceiling, as that
  // specification's cap chain asks). The newer specification runs BULK as
  // pure CC with the hold timer, so a small or high-resistance bank can climb
  // from BulkVoltage to the hard-shutdown trip (Bulk + 0.3 V) before
  // bulkVoltageHoldMs elapses and cycle through warning ramps and lockouts
  // forever, never charging (seen in the simulator with a 40 Ah AGM bank at
  // 50 A). Once IBV reaches BulkVoltage in BULK, the CV loop engages at the
  // bulk target (bumpless, Groups 1-3 armed) until IBV falls
  // BULK_V_BAND_EXIT below it; the stage machine is untouched.
  const bool overrideTargets = overrideNow || p.TuningMode;
  if (stages_.inBulkStage() && !overrideTargets && finite(in.IBV)) {
    if (!bulkVoltageLimitActive_ && in.IBV >= p.BulkVoltage)
      bulkVoltageLimitActive_ = true;
    else if (bulkVoltageLimitActive_ && in.IBV < p.BulkVoltage - k::BULK_V_BAND_EXIT)
      bulkVoltageLimitActive_ = false;
  } else {
    bulkVoltageLimitActive_ = false;
  }
  if (bulkVoltageLimitActive_) voltageControlActive_ = true;
  if (p.CVTuningMode) {
    ChargingVoltageTarget_ = cvTuning_.target(in.now, ChargingVoltageTarget_, p);
    voltageControlActive_ = true;
  } else if (cvTuning_.running()) {
    cvTuning_.reset();  // nothing to clear unless a run is in progress (score/commit need one)
  }
  if (p.TargetVoltageMode) {
    ChargingVoltageTarget_ = targetVoltageSetpointV(p);
    voltageControlActive_ = true;
  }
  if (p.MaintainMode) {
    // CV runs at the bulk target so Groups 1/2 stay armed; the ceiling is 0.
    ChargingVoltageTarget_ = p.BulkVoltage;
    voltageControlActive_ = true;
  } else if (idleZeroCurrentHold(p)) {
    // The resting bank: zero battery current under a FloatVoltage ceiling.
    ChargingVoltageTarget_ = p.FloatVoltage;
    voltageControlActive_ = true;
  }
  // Not set up (config/setup_pending.h): no target above the charge ceiling,
  // whichever mode or stored value asks for it (docs/configuration.md "Not
  // set up"). The running layer already lowered the values; this holds even
  // for a target computed from several of them.
  if (p.SetupCeilingV > 0.0 && ChargingVoltageTarget_ > p.SetupCeilingV)
    ChargingVoltageTarget_ = p.SetupCeilingV;
  // The BMS's CVL is a ceiling on every target, overrides included, and the
  // voltage loop runs under it from the start (it sits at its current ceiling
  // while below): engaging it only once IBV reached CVL overshoots by the
  // loop's reaction time.
  if (std::isfinite(in.bmsCvlV) && in.bmsCvlV < ChargingVoltageTarget_ + k::BULK_V_BAND_EXIT) {
    ChargingVoltageTarget_ = std::min(ChargingVoltageTarget_, in.bmsCvlV);
    voltageControlActive_ = true;
  }
  if (p.TuningMode) voltageControlActive_ = false;  // characterise the inner loop alone
}

}  // namespace xr
