#pragma once
// updateChargingStage(): BULK / ABSORPTION / FLOAT / IDLE as the specification's
// charging-stage state machine, with the re-bulk and resume rules of
// docs/deviations.md and docs/batteries.md. Drives inBulkStage,
// inAbsorptionStage, inIdleStage, voltageControlActive and
// ChargingVoltageTarget.
#include "core/modes.h"
#include "core/time.h"
#include "params/params.h"

namespace xr {

struct StageInputs {
  TimeNs now = 0;
  double v = 0.0;     // IBV
  double Bcur = 0.0;  // + = charging
  double thermalPenaltyAmps = 0.0;
  double uTargetAmps = 0.0;
  double SOC_percent = 0.0;
  bool socValid = false;  // SOC gating only with a real SoC
  // The voltage loop holds the absorption target (not a current ceiling):
  // only then is a low Bcur a tail (docs/deviations.md "Tail current").
  bool voltageHeld = true;
  // MaintainMode / TargetVoltageMode / CVTuningMode / manual: those set the
  // target themselves and the stage machine holds (timers cleared).
  bool suppressed = false;
};

class ChargingStageMachine {
 public:
  // Returns true when the stage changed this call.
  // Real-time thread, every tick: neither allocates nor blocks (docs/architecture.md "Threads").
  bool updateChargingStage(const StageInputs& in, const Params& p) noexcept;
  // enterSysAuto(): BULK, timers reset.
  void resetToBulk(TimeNs now) noexcept;
  // Back in AUTO after `away` out of it: resume ABSORPTION / FLOAT when the
  // absence was short (StageResumeMaxSec), else BULK (docs/deviations.md
  // "Return to AUTO"). Returns true when the stage was kept.
  bool resumeOrBulk(TimeNs now, TimeNs away, const Params& p) noexcept;

  ChargeStage stage() const noexcept { return stage_; }
  bool inBulkStage() const noexcept { return stage_ == ChargeStage::BULK; }
  bool inAbsorptionStage() const noexcept { return stage_ == ChargeStage::ABSORPTION; }
  bool inFloatStage() const noexcept { return stage_ == ChargeStage::FLOAT; }
  bool inIdleStage() const noexcept { return stage_ == ChargeStage::IDLE; }
  // chargingEnabled is false in IDLE (folded into the tick snapshot).
  bool chargingEnabled() const noexcept { return stage_ != ChargeStage::IDLE; }
  bool voltageControlActive() const noexcept {
    return stage_ == ChargeStage::ABSORPTION || stage_ == ChargeStage::FLOAT;
  }
  double ChargingVoltageTarget(const Params& p) const noexcept {
    switch (stage_) {
      case ChargeStage::ABSORPTION:
        return p.AbsorptionVoltage;
      case ChargeStage::FLOAT:
      case ChargeStage::IDLE:
        return p.FloatVoltage;
      case ChargeStage::BULK:
      default:
        return p.BulkVoltage;
    }
  }
  bool tailSuppressedByThermal() const noexcept { return tailThermalSuppressed_; }
  // True on the call where absorption ended on its tail current: the bank is
  // full (the battery monitor takes it as a detected full charge).
  bool completedOnTail() const noexcept { return completedOnTail_; }
  // Net Ah out of the bank since float/idle began (RebulkDischarge_percent).
  double restDischargedAh() const noexcept { return restOutAh_; }
  bool rebulkBlockedBySoc() const noexcept { return rebulkBlockedBySoc_; }

 private:
  // A gap longer than this between calls (the machine was suppressed) is
  // not counted: the battery current then is not known to have flowed.
  static constexpr double kMaxCountGapS = 1.0;

  void enter(ChargeStage s, TimeNs now) noexcept;
  void countRestDischarge(const StageInputs& in) noexcept;
  bool rebulkDue(const StageInputs& in, const Params& p) noexcept;

  ChargeStage stage_ = ChargeStage::BULK;     // the stage now
  ChargeStage previous_ = ChargeStage::BULK;  // the stage before the last change (resume after an absence)
  TimeNs stageStart_ = 0;                     // when the stage was entered
  bool bulkHoldArmed_ = false;                // IBV reached BulkVoltage: the bulk hold counts
  TimeNs bulkVoltageHoldTimer_ = 0;           // since when (bulkVoltageHoldMs)
  bool tailArmed_ = false;                    // the tail current holds: the absorption exit counts
  TimeNs tailStart_ = 0;                      // since when
  bool tailThermalSuppressed_ = false;        // a thermal derate holds the tail off (not a full bank)
  TimeNs absorptionStartTime_ = 0;            // absorption began (its timeout)
  bool rebulkArmed_ = false;                  // the re-bulk condition holds (rebulkDebounceTime counts)
  TimeNs rebulkStart_ = 0;                    // since when
  bool rebulkBlockedBySoc_ = false;           // the SoC gate held a re-bulk back this tick
  bool completedOnTail_ = false;              // absorption ended on the tail this tick (a full bank)
  TimeNs lastNow_ = -1;                       // the last call (the discharge count's dt)
  double restOutAh_ = 0.0;  // Ah discharged since float / idle began (RebulkDischarge_percent)
};

}  // namespace xr
