// Regulator::step: one control tick, in the order of docs/control.md
// "Order of one tick" (the battery after the outputs: docs/batteries.md):
//
//   auto-zero -> corrected sensors + filters -> protection detectors
//   (sustained timers) -> charging stage -> TickSnapshot -> mode selection ->
//   mode transitions (enterSys*) -> shutdown path (incl. applyImmediateCut)
//   or normal control (AUTO with fast-OV supervisors / MANUAL / Limp Home)
//   -> governor -> outputs -> SoC update -> charging held -> alarms -> alternator wear and belt
//   slip -> telemetry.
//
// CH1 freshness: the control law (filters, CV loop, PID, governor) fires on
// fresh CH1 samples. On other ticks the protections, the shutdown sequencer,
// the fast-OV supervisors and MANUAL / Limp Home still run; in AUTO the PID
// and the duty hold (GOV_HOLD semantics) until the next sample.
#include <algorithm>
#include <cmath>

#include "control/regulator.h"
#include "control/regulator_state.h"
#include "control/temp_compensation.h"
#include "core/alternator_temperature.h"
#include "core/freshness.h"
#include "params/derived.h"

namespace xr {

namespace {
bool isRampMode(FieldControlMode m) {
  return m == FieldControlMode::MODE_CRITICAL_RAMP || m == FieldControlMode::MODE_WARNING_RAMP_AND_LOCKOUT ||
         m == FieldControlMode::MODE_LOCKOUT_RAMP;
}
}  // namespace

const Outputs& Regulator::step(const Inputs& in) noexcept {
  Tick t(in);
  beginTick(t);
  if (s_->p.SetupBankFromBattery && !settleBankClass(t)) return s_->out;
  readSensors(t);
  runProtections(t);
  t.d = selectMode(t);
  enterMode(t);
  t.act = decideDuty(t);
  applyField(t);
  updateBattery(t);
  updateHealth(t);
  fillInputTelemetry(t);
  fillStateTelemetry(t);
  fillCapsTelemetry(t);
  return s_->out;
}

// The events of commands applied since the last step open this step's batch.
void Regulator::beginTick(const Tick& t) noexcept {
  State& s = *s_;
  s.out.events.clear();
  s.pending.drainInto(s.out.events);
  s.now = t.in.now;
}

// 1. Auto-zero BEFORE the control step (it owns GPIO4 while active).
// 2. Corrected sensors and the CH1 record-path filters.
void Regulator::readSensors(Tick& t) noexcept {
  State& s = *s_;
  const Inputs& in = t.in;
  const Params& p = s.p;
  EventBatch& ev = s.out.events;
  s.bat.checkAutoZeroTriggers(in, ev);
  t.autoZeroActive = s.bat.processAutoZero(in, ev);
  t.temp = &alternatorTemperature(in, p.TempSource);
  ControlSensors& cs = t.cs;
  cs.now = in.now;
  cs.ch1Fresh = in.altCurrentRaw.fresh;
  cs.MeasuredAmps =
      std::isfinite(in.altCurrentRaw.value) ? s.bat.correctedAltAmps(in.altCurrentRaw.value) : kNoValue;
  cs.IBV = in.IBV.value;
  cs.ibvFresh = in.IBV.fresh;
  cs.Bcur = std::isfinite(in.Bcur.value) ? s.bat.correctedBcur(in.Bcur.value) : kNoValue;
  cs.rpm = in.rpm.value;
  cs.TempToUse = t.temp->value;
  cs.tempStamp = t.temp->stamp;
  cs.SOC_percent = s.bat.socPercent();
  cs.socKnown = s.bat.socKnown();
  s.law.updateFilters(cs, p);
}

// 3. Protection detectors and sustained timers, the battery's temperature
// rules; 4. the BMS's limits, then the charging stage.
void Regulator::runProtections(Tick& t) noexcept {
  State& s = *s_;
  const Inputs& in = t.in;
  const Params& p = s.p;
  EventBatch& ev = s.out.events;
  // A resting field (last tick) quiets the tach: the RPM gate must know it is not a stopped engine.
  s.prot.setFieldResting(s.law.fieldResting());
  s.prot.updateDetectors(in, t.cs.MeasuredAmps, ev);
  const ProtectionFlags& f = s.prot.flags();
  t.cs.sensorFailureBypass = f.voltageImplausible || f.voltageDisagreeCritical;
  // Battery temperature (docs/batteries.md): cold/hot orders, current cap, and the
  // compensated targets the stage machine and the voltage loop see.
  const BatteryTempDecision& bt = s.batTemp.update(in, p, ev);
  t.cs.batteryChargeCapA = bt.currentCapA;
  const double compV = temperatureCompensationV(p, bt.tempC);
  const Params* stageParams = &p;
  if (compV != 0.0) {
    compensateTargets(p, compV, s.compensated);
    stageParams = &s.compensated;
  }
  // The charging stage is suppressed in override modes and manual.
  s.law.updateBms(in.bms, in.now, t.cs.Bcur, in.IBV.value, p, ev);
  s.law.updateChargingStage(t.cs, *stageParams, s.ops.manualMode(p), ev);
}

// 5. Immutable snapshot and mode selection by priority.
ModeDecision Regulator::selectMode(Tick& t) noexcept {
  State& s = *s_;
  const Params& p = s.p;
  const BatteryTempDecision& bt = s.batTemp.decision();
  TickSnapshot& snap = t.snap;
  snap.now = t.in.now;
  snap.prot = s.prot.flags();
  snap.limpHome = s.ops.limpHome();
  snap.manualMode = s.ops.manualMode(p);
  snap.sysOff = s.ops.off();
  snap.ignitionOn = t.in.ignitionOn;
  snap.OnOff = p.OnOff;
  snap.bmsChargeEnabled = t.in.bmsChargeEnabled && s.law.bms().chargeAllowed();
  // A floor the forecast does not get to argue with (docs/deviations.md
  // "Weather mode's SoC floor"): below it, or with the SoC unknown, charge.
  snap.weatherModeActive =
      p.weatherModeEnabled && s.ops.weatherMode() && t.cs.socKnown && t.cs.SOC_percent >= p.WeatherModeMinSoC;
  // IDLE rests the field, unless the alternator carries the house loads
  // while the bank rests (IdleZeroCurrent).
  snap.idleStage = s.law.stages().inIdleStage() && !s.law.idleZeroCurrentHold(p);
  snap.batteryCold = bt.cold;
  snap.batteryHot = bt.hot;
  snap.autoZeroActive = t.autoZeroActive;
  return selectFieldMode(snap);
}

// 6. Mode transitions: bumpless enterSys* and the mode-change event.
void Regulator::enterMode(const Tick& t) noexcept {
  State& s = *s_;
  const ModeDecision& d = t.d;
  if (s.report.changes(d)) {
    switch (d.mode) {
      case FieldControlMode::MODE_NORMAL_AUTO_PID:
        s.law.enterSysAuto(t.cs, s.p);
        if (!s.report.firstTick() && isRampMode(s.report.mode())) s.law.onProtectionCleared(t.in.now);
        break;
      case FieldControlMode::MODE_NORMAL_MANUAL:
      case FieldControlMode::MODE_LIMP_HOME:
        s.law.enterSysManual();
        break;
      case FieldControlMode::MODE_DISABLED_RAMP:
        s.law.enterSysOff();
        break;
      default:
        s.law.enterSysFault();
        break;
    }
  }
  const bool rpmUnread = d.reason == Reason::REASON_RPM_LOW && !std::isfinite(t.in.rpm.value);
  s.report.noteMode(d, rpmUnread, t.in.now, s.out.events);
}

// 7. The shutdown path every tick (it tracks transitions), else the mode's
// control; the auto-zero and a non-finite duty leave the field off.
DutyDecision Regulator::decideDuty(const Tick& t) noexcept {
  State& s = *s_;
  const Params& p = s.p;
  EventBatch& ev = s.out.events;
  DutyDecision a;
  const ShutdownCommand sc = s.prot.runShutdownPath(t.d, s.law.lastAppliedDuty(), s.law.rpmMinDuty(), ev);
  if (sc.applyImmediateCut) s.law.applyImmediateCut();
  if (sc.active) {
    a.duty = sc.dutyPct;  // already slewed by the phase rates (effective minimum 0)
    a.field = sc.fieldEnable;
    a.govMode = sc.govMode;
    s.law.trackShutdown(a.duty, p, t.cs.rpm);
  } else if (t.d.mode == FieldControlMode::MODE_LIMP_HOME) {
    a.duty = s.law.runLimpHome(t.cs, p, ev);
    a.field = true;
  } else if (t.d.mode == FieldControlMode::MODE_NORMAL_MANUAL) {
    a.duty = s.law.runManual(t.cs, p, s.ops.manualDuty(p));
    a.field = true;
  } else if (t.d.mode == FieldControlMode::MODE_NORMAL_AUTO_PID) {
    a = runAuto(t);
  } else {
    // A non-normal mode the sequencer did not take: the safe state.
    a.duty = 0.0;
    a.field = false;
    s.law.trackShutdown(0.0, p, t.cs.rpm);
  }
  if (t.autoZeroActive) {
    // The auto-zero owns the field: LOW for the whole measurement.
    a.field = false;
    a.duty = 0.0;
    s.law.trackShutdown(0.0, p, t.cs.rpm);
  }
  if (!std::isfinite(a.duty)) {
    a.duty = 0.0;
    a.field = false;
  }
  return a;
}

// AUTO: the current target, the fast over-voltage supervisors' say over it,
// then the inner loop and the governor.
DutyDecision Regulator::runAuto(const Tick& t) noexcept {
  State& s = *s_;
  const Params& p = s.p;
  const double uTargetRaw = s.law.computeUTarget(t.cs, p);
  FastOvInputs fi;
  fi.voltageControlActive = s.law.voltageControlActive();
  fi.floatStage = s.law.stages().inFloatStage();
  fi.ChargingVoltageTarget = s.law.ChargingVoltageTarget();
  fi.uTargetAmps = uTargetRaw;
  fi.setpointLimited = s.law.setpointLimited();
  fi.cv_I = s.law.cv_I();
  fi.MeasuredAmps = t.cs.MeasuredAmps;
  fi.MeasuredAmps_filtered = s.law.MeasuredAmps_filtered();
  fi.altCurrentFresh = t.in.altCurrentRaw.fresh;
  FastOvVerdict ov = s.prot.runFastOvSupervisors(fi).verdict;
  // A belt-slip probe holds the target low for a few seconds (docs/operations.md "Belt slip").
  ov.fastOvCurrentCap = std::min(ov.fastOvCurrentCap, s.belt.probeCapA());
  DutyDecision a;
  a.duty = s.law.finishAuto(t.cs, p, ov, s.out.events);
  a.field = !s.law.fieldResting();  // a full bank at the RPM floor rests the field
  a.fastOvActive = ov.fastOvClampActive;
  a.govMode = s.law.govMode();
  return a;
}

// The field enable's edges, then the outputs the drivers write.
void Regulator::applyField(const Tick& t) noexcept {
  State& s = *s_;
  Outputs& out = s.out;
  const bool field = t.act.field;
  if (s.report.noteField(field, t.d, t.in.now, out.events)) s.law.onFieldTurnOn(t.in.now);
  out.dutyPct = field ? std::clamp(t.act.duty, 0.0, 100.0) : 0.0;
  out.fieldEnable = field;
  out.inaFastMode = field;  // fast conversions while the field is on (Group 1 dv/dt, ALERT speed)
  out.inaBovlVolts = voltageHardwareLimit(s.p);
}

// 8. SoC and energy; 9. alarms (250 ms cadence inside).
void Regulator::updateBattery(const Tick& t) noexcept {
  State& s = *s_;
  EventBatch& ev = s.out.events;
  s.bat.updateBatterySoc(t.in, t.cs.MeasuredAmps, ev);
  if (s.law.stages().completedOnTail()) s.bat.chargeCompletedOnTail(t.in.now, ev);
  s.prot.setBmsStale(s.law.bms().stale());
  updateChargeChecks(t);
  s.out.buzzer = s.prot.checkAlarms(false, ev);
}

// 9b. What the regulator learns about the alternator: wear and belt slip
// (docs/operations.md "Alternator wear", "Belt slip").
void Regulator::updateHealth(const Tick& t) noexcept {
  State& s = *s_;
  const Inputs& in = t.in;
  const double dt =
      s.lastHealthTick != 0 && in.now > s.lastHealthTick ? toSec(in.now - s.lastHealthTick) : 0.0;
  s.lastHealthTick = in.now;
  const bool turning = fresh::engineTurning(in.rpm.value) ||
                       (std::isfinite(t.cs.MeasuredAmps) && t.cs.MeasuredAmps > s.p.CurrentThreshold);
  // The temperature the protections act on counts, and only that: a reading
  // out of the sensor's range must not add to the insulation life used.
  const bool tempKnown = fresh::alternatorTemp(*t.temp, in.now);
  s.wear.update(dt, turning, tempKnown ? t.temp->value : kNoValue, t.cs.MeasuredAmps, s.p);
  BeltSample b;
  b.rpm = in.rpm.value;
  const bool engineFresh = fresh::engineRpm(in.engineRpm, in.now);
  b.engineRpm = engineFresh ? in.engineRpm.value : kNoValue;
  b.altAmps = t.cs.MeasuredAmps;
  b.dutyPct = s.out.dutyPct;
  b.targetAmps = s.law.uTargetAmps();
  b.fieldOn = s.out.fieldEnable && t.d.mode == FieldControlMode::MODE_NORMAL_AUTO_PID;
  b.engineHeard = engineFresh;
  b.ratedA = s.p.MaxTableValue;
  if (s.belt.update(in.now, dt, b, s.out.events)) s.wear.countBeltSlip();
}

// 10. Telemetry: this tick's inputs and decisions (the modules' state after
// the step is fillStateTelemetry's).
void Regulator::fillInputTelemetry(const Tick& t) noexcept {
  State& s = *s_;
  const Inputs& in = t.in;
  Telemetry& tm = s.out.telemetry;
  tm.now = in.now;
  tm.mode = t.d.mode;
  // A stale BMS only caps the charge (no mode change): the reason still says so.
  tm.reason = t.d.reason == Reason::NONE && s.law.bms().stale() ? Reason::REASON_BMS_STALE : t.d.reason;
  tm.ibv_v = in.IBV.value;
  tm.battery_v = in.BatteryV.value;
  tm.bcur_a = t.cs.Bcur;
  tm.alt_a = t.cs.MeasuredAmps;
  tm.rpm = in.rpm.value;
  tm.temp_f = t.temp->value;
  tm.battery_temp_c = in.batteryTempC.value;
  tm.duty_pct = s.out.dutyPct;
  tm.field_enable = s.out.fieldEnable;
  tm.ignition_on = in.ignitionOn;
  tm.fast_ov_active = t.act.fastOvActive;
  tm.alarm = s.out.buzzer;
}

// The telemetry that reads the modules' state after this step.
void Regulator::fillStateTelemetry(const Tick& tick) noexcept {
  State& s = *s_;
  Telemetry& t = s.out.telemetry;
  s.law.fillTelemetry(t.control);
  t.control.govMode = tick.act.govMode;
  t.control.limpHome = s.report.mode() == FieldControlMode::MODE_LIMP_HOME;
  s.prot.fillTelemetry(t.protection);
  s.bat.updateTelemetry(t.battery);
  s.wear.fillTelemetry(t.wear);
  t.wear.belt_slipping = s.belt.slipping();
  t.stage = s.law.stages().stage();
  t.setupBank = s.bank.shown();
  t.setpoint_a = s.law.setpointLimited();
  t.target_a = s.law.uTargetAmps();
  t.target_v = s.law.ChargingVoltageTarget();
  t.thermal_penalty_a = s.law.thermalPenaltyAmps();
  t.soc_pct = t.battery.SOC_percent;  // the same socPercent(), already in the battery telemetry
  // chargedEnergyLifetimeWh() and alternatorChargedEnergyLifetimeWh(), as filled just above.
  t.charged_wh_lifetime = t.battery.ChargedEnergy_AllTime_Wh;
  t.alt_charged_wh_lifetime = t.battery.AlternatorChargedEnergy_AllTime_Wh;
  const BmsLimiter& bms = s.law.bms();
  t.bms_cvl_v = bms.shownCvlV();
  t.bms_ccl_a = bms.shownCclA();
  t.bms_soc_pct = bms.shownSocPct();
  t.bms_state = bms.state();
  t.bms_mismatch = bms.plausibility().reported();
  t.charge_held_by = s.hold.cause();
  t.charge_held_min = s.hold.held() ? s.hold.heldS() / 60.0 : 0.0;
}

}  // namespace xr

namespace xr {

// The caps on the current command (docs/dashboard.md "Owner model"): the
// battery's every tick, the command path's only while AUTO computed them.
void Regulator::fillCapsTelemetry(const Tick& t) noexcept {
  State& s = *s_;
  CommandCaps& c = s.out.telemetry.caps;
  c = CommandCaps{};
  s.law.fillCommandCaps(c, s.p);
  if (t.d.mode != FieldControlMode::MODE_NORMAL_AUTO_PID) {
    // Computed by AUTO's command path only: last AUTO tick's, not this one's.
    c.rpmTableA = c.thermalA = c.thermalPenaltyA = c.warmupA = c.batteryCapAltA = c.fastOvA = kNoValue;
    c.commandA = kNoValue;
    c.zeroBatteryHold = false;
  }
  const BatteryTempDecision& bt = s.batTemp.decision();
  if (bt.capCause != BatteryTempCap::NONE) {
    c.batteryTempA = bt.currentCapA;
    c.batteryTempCause = bt.capCause;
  }
  const double bmsCap = s.law.bms().batteryCapA();
  if (std::isfinite(bmsCap)) c.bmsA = bmsCap;
  c.bmsSource = t.in.bms.source;
}

}  // namespace xr
