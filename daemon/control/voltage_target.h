#pragma once
// VoltageTarget: the voltage the bank is held at and whether the voltage
// loop runs (docs/control.md "Charging stages", "Override modes"): the
// charging stage machine's target, then the bulk ceiling, CVTuningMode,
// TargetVoltageMode, MaintainMode, the idle hold, the not-set-up ceiling and
// the BMS's CVL, in that order.
#include "control/charging_stage.h"
#include "control/cv_tuning_mode.h"
#include "core/events.h"
#include "core/inputs.h"
#include "params/params.h"

namespace xr {

// What the target reads each tick (before mode selection).
struct TargetInputs {
  TimeNs now = 0;
  double IBV = kNoValue;
  double Bcur = kNoValue;
  double SOC_percent = kNoValue;
  bool socKnown = true;
  double thermalPenaltyAmps = 0.0;
  double uTargetAmps = 0.0;      // the current command (last AUTO tick)
  double setpointCommand = 0.0;  // the outer loops' command (last fresh tick)
  bool fieldResting = false;
  bool manualMode = false;
  bool autoMode = false;      // the control law is in SYS_MODE_AUTO
  double bmsCvlV = kNoValue;  // the BMS's CVL ceiling (NaN: none)
};

class VoltageTarget {
 public:
  // One tick: stage machine (StageChanged event on a change), then the target.
  void update(const TargetInputs& in, const Params& p, EventBatch& ev) noexcept;
  // Back in AUTO after an absence of `away` (-1: first time).
  void resume(TimeNs now, TimeNs away, const Params& p) noexcept { stages_.resumeOrBulk(now, away, p); }
  void scoreCvTuning(double IBV, double dtSec, const Params& p) noexcept { cvTuning_.score(IBV, dtSec, p); }
  bool commitCvTuning(TimeNs now, const Params& p) noexcept { return cvTuning_.commit(now, p); }

  // IDLE with IdleZeroCurrent: the bank rests while the alternator carries
  // the house loads (docs/batteries.md "After absorption"). Not an override:
  // the stage machine keeps its re-bulk watch.
  bool idleZeroCurrentHold(const Params& p) const noexcept {
    return p.IdleZeroCurrent && stages_.inIdleStage() && !p.MaintainMode && !p.TargetVoltageMode &&
           !p.CVTuningMode;
  }
  bool voltageControlActive() const noexcept { return voltageControlActive_; }
  double ChargingVoltageTarget() const noexcept { return ChargingVoltageTarget_; }
  bool bulkVoltageLimitActive() const noexcept { return bulkVoltageLimitActive_; }
  const ChargingStageMachine& stages() const noexcept { return stages_; }
  const CvTuningModeRunner& cvTuning() const noexcept { return cvTuning_; }

  explicit VoltageTarget(const Params& p) : ChargingVoltageTarget_(p.BulkVoltage) {}

 private:
  // The CV loop is "at its ceiling" when its command is within this of it.
  static constexpr double kTailHeadroomA = 1.0;

  void applyOverrides(const TargetInputs& in, const Params& p, bool overrideNow) noexcept;

  ChargingStageMachine stages_;        // BULK / ABSORPTION / FLOAT / IDLE (docs/control.md "Charging stages")
  CvTuningModeRunner cvTuning_;        // CVTuningMode's voltage wave and its score
  bool voltageControlActive_ = false;  // the voltage loop runs this tick
  double ChargingVoltageTarget_;       // the voltage it holds
  bool bulkVoltageLimitActive_ = false;  // the bulk ceiling engaged the voltage loop in BULK
  bool overrideWasActive_ = false;       // an override mode ran last tick (its end resumes the stage)
  TimeNs overrideSince_ = -1;            // when the override began
};

}  // namespace xr
