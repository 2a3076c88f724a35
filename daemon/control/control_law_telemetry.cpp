// ControlLaw's telemetry block: every loop variable under its seed name.
#include <algorithm>
#include <cmath>

#include "control/control_law.h"
#include "control/rpm_tables.h"

namespace xr {

void ControlLaw::fillTelemetry(ControlTelemetry& t) const noexcept {
  fillLoopTelemetry(t);
  fillTuningTelemetry(t);
}

void ControlLaw::fillLoopTelemetry(ControlTelemetry& t) const noexcept {
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
  t.innerTermP = currentPID_.pTerm();
  t.innerTermI = currentPID_.iTerm();
  t.innerTermD = currentPID_.dTerm();
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

void ControlLaw::fillCommandCaps(CommandCaps& c, const Params& p) const noexcept {
  auto ifBelow = [](double cap) { return cap < kNoCeiling ? cap : kNoValue; };
  c.ratingA = p.MaxTableValue;
  c.rpmTableA = I_cap_;
  // The table's top is the belt limit the set-up writes (in amps only: the power table's top moves with
  // volts).
  const RpmTable& table = activeCapCurrentTable(p);
  c.rpmTableTopA = p.capLimitMode == 1 ? kNoValue : *std::max_element(table.begin(), table.end());
  c.batteryMaxA = p.MaximumAllowedBatteryAmps;
  const double penalty = thermal_.thermalPenaltyAmps();
  c.thermalPenaltyA = penalty > 0.0 ? penalty : kNoValue;
  c.thermalA = penalty > 0.0 ? std::max(0.0, I_cap_ - penalty) : kNoValue;
  c.warmupA = warmupActive_ ? p.WarmupCeilingAmps : kNoValue;
  c.batteryCapAltA = ifBelow(bmsAltCap_);
  c.fastOvA = fastOvClampActive_ ? ifBelow(fastOvCapA_) : kNoValue;
  c.zeroBatteryHold = holdsZeroBatteryCurrent(p);
  c.commandA = I_cmd_;
}

void ControlLaw::fillTuningTelemetry(ControlTelemetry& t) const noexcept {
  t.tuningRunning = tuning_.running();
  t.tuningHighPhase = tuning_.highPhase();
  t.tuningScore = tuning_.currentScore();
  t.tuningLogCount = tuning_.logCount();
  t.cvTuningRunning = cvTuning_.running();
  t.cvTuningScore = cvTuning_.currentScore();
  t.cvTuningSettleSec = cvTuning_.lastSettleSec();
  t.cvTuningLogCount = cvTuning_.logCount();
  t.sysIDRunning = sysId_.systemIdRunning();
  t.sysIDDutyOut = sysIdDutyOut_;
  t.sysIDValid = sysId_.result().valid;
  t.sysIDDeadTimeMs = sysId_.result().deadTimeMs;
  t.sysIDRiseTimeMs = sysId_.result().riseTimeMs;
  t.sysIDSlopeAps = sysId_.result().slopeAps;
}

}  // namespace xr
