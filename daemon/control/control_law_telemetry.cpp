// ControlLaw's telemetry block: every loop variable under the name the
// specification gives it.
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
  t.govMode = inner_.govMode();
  t.I_cap = command_.I_cap();
  t.I_cmd = command_.I_cmd();
  t.uTargetRaw = command_.uTargetRaw();
  t.uTargetAmps = command_.uTargetAmps();
  t.setpointCommand = slew_.setpointCommand();
  t.setpointLimited = slew_.setpointLimited();
  t.pidInput = inner_.pid().input;
  t.pidOutput = inner_.pid().output;
  t.innerTermP = inner_.pid().pTerm();
  t.innerTermI = inner_.pid().iTerm();
  t.innerTermD = inner_.pid().dTerm();
  t.dutyRequest = inner_.dutyRequest();
  t.lastAppliedDuty = inner_.lastAppliedDuty();
  t.rpmMinDuty = inner_.rpmMinDuty();
  t.voltageControlActive = targets_.voltageControlActive();
  t.ChargingVoltageTarget = targets_.ChargingVoltageTarget();
  t.voltageTargetSlewed = cv_.voltageTargetSlewed();
  t.cv_I = cv_.cv_I();
  t.Icv = cv_.Icv();
  t.cv_I_track = cv_.cv_I_track();
  t.cv_I_aw_cap = cv_.cv_I_aw_cap();
  t.g_awState = cv_.g_awState();
  t.cvDSlope = cv_.cvDSlope();
  t.g_voltLoopActualIntervalMs = cv_.g_voltLoopActualIntervalMs();
  t.tempFiltered = thermal().tempFiltered();
  t.projectedTempF = thermal().projectedTempF();
  t.thermalSlopeFPerSec = thermal().thermalSlopeFPerSec();
  t.thermalPenaltyAmps = thermal().thermalPenaltyAmps();
  t.thermalPenaltyAmps_d = thermal().penaltyTarget();
  t.thermalHolding = thermal().holding();
  t.MeasuredAmps = filters_.measuredAmps();
  t.MeasuredAmps_filtered = filters_.input().value();
  t.g_pidI_filtered = filters_.pidFiltered().value();
  t.g_pidMA_N = filters_.pidMovingAverage();
  t.IBV_filtered = filters_.ibvFiltered().value();
  t.inStartupRamp = slew_.inStartupRamp();
  t.fastRiseActive = slew_.fastRiseActive();
  t.warmupActive = command_.warmupActive();
  t.bulkVoltageLimitActive = targets_.bulkVoltageLimitActive();
  t.fastOvClampActive = fastOv_.clampActive();
  t.cvOvershootBypass = fastOv_.overshootBypass();
  t.inBulkStage = stages().inBulkStage();
  t.inAbsorptionStage = stages().inAbsorptionStage();
  t.inFloatStage = stages().inFloatStage();
  t.inIdleStage = stages().inIdleStage();
  t.tailSuppressedByThermal = stages().tailSuppressedByThermal();
  t.rebulkBlockedBySoc = stages().rebulkBlockedBySoc();
}

void ControlLaw::fillCommandCaps(CommandCaps& c, const Params& p) const noexcept {
  auto ifBelow = [](double cap) { return cap < CurrentCommand::kNoCeiling ? cap : kNoValue; };
  c.ratingA = p.MaxTableValue;
  c.rpmTableA = command_.I_cap();
  // The table's top is the belt limit the set-up writes (in amps only: the power table's top moves with
  // volts).
  const RpmTable& table = activeCapCurrentTable(p);
  c.rpmTableTopA = p.capLimitMode == 1 ? kNoValue : *std::max_element(table.begin(), table.end());
  c.batteryMaxA = p.MaximumAllowedBatteryAmps;
  const double penalty = thermal().thermalPenaltyAmps();
  c.thermalPenaltyA = penalty > 0.0 ? penalty : kNoValue;
  c.thermalA = penalty > 0.0 ? std::max(0.0, command_.I_cap() - penalty) : kNoValue;
  c.warmupA = command_.warmupActive() ? p.WarmupCeilingAmps : kNoValue;
  c.batteryCapAltA = ifBelow(command_.bmsAltCap());
  c.fastOvA = fastOv_.clampActive() ? ifBelow(fastOv_.capA()) : kNoValue;
  c.zeroBatteryHold = holdsZeroBatteryCurrent(p);
  c.commandA = command_.I_cmd();
}

void ControlLaw::fillTuningTelemetry(ControlTelemetry& t) const noexcept {
  t.tuningRunning = tuning_.running();
  t.tuningHighPhase = tuning_.highPhase();
  t.tuningScore = tuning_.currentScore();
  t.tuningLogCount = tuning_.logCount();
  t.cvTuningRunning = cvTuning().running();
  t.cvTuningScore = cvTuning().currentScore();
  t.cvTuningSettleSec = cvTuning().lastSettleSec();
  t.cvTuningLogCount = cvTuning().logCount();
  t.sysIDRunning = sysId_.systemIdRunning();
  t.sysIDDutyOut = sysIdDutyOut_;
  t.sysIDValid = sysId_.result().valid;
  t.sysIDDeadTimeMs = sysId_.result().deadTimeMs;
  t.sysIDRiseTimeMs = sysId_.result().riseTimeMs;
  t.sysIDSlopeAps = sysId_.result().slopeAps;
}

}  // namespace xr
