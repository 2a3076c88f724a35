#include "control/charging_stage.h"

#include <algorithm>
#include <cmath>

#include "params/constants.h"
#include "params/derived.h"

namespace xr {

void ChargingStageMachine::enter(ChargeStage s, TimeNs now) noexcept {
  previous_ = stage_;
  stage_ = s;
  stageStart_ = now;
  bulkHoldArmed_ = tailArmed_ = rebulkArmed_ = false;
  tailThermalSuppressed_ = false;
  completedOnTail_ = false;
  restOutAh_ = 0.0;
  if (s == ChargeStage::ABSORPTION) absorptionStartTime_ = now;
}

void ChargingStageMachine::resetToBulk(TimeNs now) noexcept {
  previous_ = stage_;
  stage_ = ChargeStage::BULK;
  stageStart_ = now;
  bulkHoldArmed_ = tailArmed_ = rebulkArmed_ = false;
  tailThermalSuppressed_ = rebulkBlockedBySoc_ = completedOnTail_ = false;
  restOutAh_ = 0.0;
}

bool ChargingStageMachine::resumeOrBulk(TimeNs now, TimeNs away, const Params& p) noexcept {
  // IDLE resumes too: a bank resting after its charge (IdleZeroCurrent) is
  // still full after an engine restart, and its counted discharge goes on.
  const bool resumable =
      stage_ == ChargeStage::ABSORPTION || stage_ == ChargeStage::FLOAT || stage_ == ChargeStage::IDLE;
  if (resumable && p.StageResumeMaxSec > 0.0 && away >= 0 && away <= fromSec(p.StageResumeMaxSec)) {
    // Timers keep running from their stage start (an absorption's timeout
    // counts the pause); the debounces restart.
    bulkHoldArmed_ = tailArmed_ = rebulkArmed_ = false;
    return true;
  }
  resetToBulk(now);
  return false;
}

// Net amp-hours taken out of the bank since float/idle began (charge counts
// back, never below zero): what RebulkDischarge_percent compares.
void ChargingStageMachine::countRestDischarge(const StageInputs& in) noexcept {
  const double dtS = lastNow_ < 0 ? 0.0 : toSec(in.now - lastNow_);
  if (dtS > 0.0 && dtS < kMaxCountGapS && std::isfinite(in.Bcur))
    restOutAh_ = std::max(0.0, restOutAh_ - in.Bcur * dtS / 3600.0);
}

// FLOAT / IDLE re-bulk: after MinFloatTime, voltage sag OR a real discharge,
// confirmed continuously for rebulkDebounceTime, with SOC gating. A real
// discharge is a discharge current over RebulkCurrent_A (the specification) or, with
// RebulkDischarge_percent set, that share of the bank counted out: a house
// load the alternator carries, or a short one it cannot, is not a discharge
// (docs/batteries.md "After absorption").
bool ChargingStageMachine::rebulkDue(const StageInputs& in, const Params& p) noexcept {
  const bool discharged = p.RebulkDischarge_percent > 0.0
                              ? restOutAh_ >= p.RebulkDischarge_percent * p.BatteryCapacity_Ah / 100.0
                              : in.Bcur < -p.RebulkCurrent_A;
  bool cond = (in.v < rebulkVoltageV(p)) || discharged;
  rebulkBlockedBySoc_ = false;
  if (in.socValid) {
    if (in.SOC_percent >= p.SOC_BlockRebulk_percent) {
      cond = false;  // full enough: never re-bulk
      rebulkBlockedBySoc_ = true;
    } else if (in.SOC_percent <= p.SOC_AllowRebulk_percent) {
      cond = true;  // low enough: re-bulk regardless of voltage/current
    }
  }
  if (in.now - stageStart_ < fromMs(p.MinFloatTime)) {
    rebulkArmed_ = false;
    return false;
  }
  if (!cond) {
    rebulkArmed_ = false;
    return false;
  }
  if (!rebulkArmed_) {
    rebulkArmed_ = true;
    rebulkStart_ = in.now;
  }
  return in.now - rebulkStart_ >= fromMs(p.rebulkDebounceTime);
}

bool ChargingStageMachine::updateChargingStage(const StageInputs& in, const Params& p) noexcept {
  completedOnTail_ = false;
  if (in.suppressed) {
    bulkHoldArmed_ = tailArmed_ = rebulkArmed_ = false;
    return false;
  }
  const ChargeStage before = stage_;
  if (stage_ == ChargeStage::FLOAT || stage_ == ChargeStage::IDLE) countRestDischarge(in);
  lastNow_ = in.now;
  switch (stage_) {
    case ChargeStage::BULK: {
      // Two-sided band: arm at Bulk - 0.05 V, clear below Bulk - 0.10 V.
      if (in.v >= p.BulkVoltage - k::BULK_V_BAND_ENTER) {
        if (!bulkHoldArmed_) {
          bulkHoldArmed_ = true;
          bulkVoltageHoldTimer_ = in.now;
        }
      } else if (in.v < p.BulkVoltage - k::BULK_V_BAND_EXIT) {
        bulkHoldArmed_ = false;
      }
      if (bulkHoldArmed_ && in.now - bulkVoltageHoldTimer_ >= fromMs(p.bulkVoltageHoldMs))
        enter(ChargeStage::ABSORPTION, in.now);
      break;
    }
    case ChargeStage::ABSORPTION: {
      // Low current from thermal derating is not "battery full".
      tailThermalSuppressed_ =
          in.thermalPenaltyAmps > k::TAIL_THERMAL_PENALTY_A && in.uTargetAmps <= 2.0 * p.TailCurrent_A;
      const bool tail = !tailThermalSuppressed_ && in.voltageHeld && in.Bcur <= p.TailCurrent_A;
      if (tail) {
        if (!tailArmed_) {
          tailArmed_ = true;
          tailStart_ = in.now;
        }
      } else {
        tailArmed_ = false;
      }
      const bool tailDone = tailArmed_ && in.now - tailStart_ >= fromMs(p.absorptionCompleteTime);
      const bool timeout = in.now - absorptionStartTime_ >= fromMs(p.AbsorptionTimeoutMs);
      if (tailDone || timeout) {
        enter(p.UseFloat ? ChargeStage::FLOAT : ChargeStage::IDLE, in.now);
        completedOnTail_ = tailDone;
      }
      break;
    }
    case ChargeStage::FLOAT: {
      if (!p.UseFloat) {
        enter(ChargeStage::IDLE, in.now);
        break;
      }
      if (in.now - stageStart_ >= fromSec(static_cast<double>(k::FLOAT_DURATION_S))) {
        enter(ChargeStage::BULK, in.now);  // unconditional after 12 h
        break;
      }
      if (rebulkDue(in, p)) enter(ChargeStage::BULK, in.now);
      break;
    }
    case ChargeStage::IDLE: {
      if (rebulkDue(in, p)) enter(ChargeStage::BULK, in.now);
      break;
    }
  }
  return stage_ != before;
}

}  // namespace xr
