// Regulator::step: one control tick, in the order of architecture-legacy.md
// "Main Loop Architecture" and battery-management.md "Critical ordering note":
//
//   auto-zero -> corrected sensors + filters -> protection detectors
//   (sustained timers) -> charging stage -> TickSnapshot -> mode selection ->
//   mode transitions (enter_sys_*) -> shutdown path (incl. applyImmediateCut)
//   or normal control (AUTO with fast-OV supervisors / MANUAL / Limp Home)
//   -> governor -> outputs -> SoC update -> alarms -> telemetry.
//
// CH1 freshness: the control law (filters, CV loop, PID, governor) fires on
// fresh CH1 samples. On other ticks the protections, the shutdown sequencer,
// the fast-OV supervisors and MANUAL / Limp Home still run; in AUTO the PID
// and the duty hold (GOV_HOLD semantics) until the next sample.
#include "control/regulator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "battery/battery_monitor.h"
#include "control/control_law.h"
#include "control/temp_compensation.h"
#include "core/alternator_temperature.h"
#include "params/derived.h"
#include "protection/battery_temperature.h"
#include "protection/mode_selection.h"
#include "protection/protection_supervisor.h"

namespace xr {

namespace {
bool isRampMode(FieldControlMode m) {
  return m == FieldControlMode::MODE_CRITICAL_RAMP || m == FieldControlMode::MODE_WARNING_RAMP_AND_LOCKOUT ||
         m == FieldControlMode::MODE_LOCKOUT_RAMP;
}
}  // namespace

struct Regulator::State {
  explicit State(const Params& params) : p(params), law(params), prot(params), bat(params) {}

  Params p;
  ControlLaw law;
  ProtectionSupervisor prot;
  BatteryMonitor bat;
  BatteryTemperatureGuard batTemp;  // docs/batteries.md "Temperature rules"
  Params compensated;               // p with temperature-compensated targets (when compensating)
  Outputs out;

  // Operator state (commands).
  bool limpHome = false;
  bool opManual = false;
  double opManualDuty = 0.0;
  bool opOff = false;
  bool currentWeatherMode = false;

  bool firstTick = true;
  FieldControlMode lastMode = FieldControlMode::MODE_DISABLED_RAMP;
  Reason lastReason = Reason::NONE;
  bool lastField = false;
  TimeNs now = 0;
  GovMode tickGovMode = GovMode::GOV_NORMAL_SLEW;  // the last step's govMode (telemetry)

  // Command results waiting for the next step's event batch.
  std::array<Event, 8> pending{};
  std::size_t pendingCount = 0;
  void queue(const Event& e) {
    if (pendingCount < pending.size()) pending[pendingCount++] = e;
  }
};

Regulator::Regulator(const Params& params) : s_(std::make_unique<State>(params)) {
  s_->out.inaBovlVolts = voltageHardwareLimit(params);
}
Regulator::~Regulator() = default;

void Regulator::setParams(const Params& params) noexcept {
  s_->p = params;
  s_->prot.setParams(params);
  s_->bat.setParams(params);
}
const Params& Regulator::params() const { return s_->p; }
const Outputs& Regulator::outputs() const { return s_->out; }
BatteryLedger Regulator::ledger() const { return s_->bat.ledger(); }
void Regulator::restoreLedger(const BatteryLedger& l) { s_->bat.restoreLedger(l); }

bool Regulator::command(const Command& cmd) noexcept {
  State& s = *s_;
  bool ok = true;
  switch (cmd.type) {
    case CommandType::Auto:
      s.opManual = false;
      s.opOff = false;
      break;
    case CommandType::Manual:
      ok = std::isfinite(cmd.value) && cmd.value >= 0.0 && cmd.value <= 100.0;
      if (ok) {
        s.opManual = true;
        s.opManualDuty = cmd.value;
        s.opOff = false;
      }
      break;
    case CommandType::Off:
      s.opOff = true;
      break;
    case CommandType::LimpHome:
      s.limpHome = true;
      break;
    case CommandType::LimpHomeOff:
      s.limpHome = false;
      break;
    case CommandType::ReenableField:
      s.prot.reenableField();
      break;
    case CommandType::ResetAlarmLatch:
      s.prot.resetAlarmLatch();
      break;
    case CommandType::ResetSocGain:
      s.bat.resetSocGain();
      break;
    case CommandType::ResetAltZero:
      s.bat.resetAltZero();
      break;
    case CommandType::SetSoc:
      ok = s.bat.setSoc(cmd.value);
      break;
    case CommandType::SystemIdStart:
      ok = !s.firstTick && s.lastMode == FieldControlMode::MODE_NORMAL_AUTO_PID && s.lastField &&
           s.law.startSystemId(s.now, true);
      break;
    case CommandType::TuningCommit:
      ok = s.p.TuningMode && s.law.commitTuning(s.now, s.p);
      break;
    case CommandType::CvTuningCommit:
      ok = s.p.CVTuningMode && s.law.commitCvTuning(s.now, s.p);
      break;
    case CommandType::WeatherMode:
      s.currentWeatherMode = cmd.flag;
      break;
  }
  EventCode code = ok ? EventCode::CommandApplied : EventCode::CommandRejected;
  if (ok && (cmd.type == CommandType::TuningCommit || cmd.type == CommandType::CvTuningCommit))
    code = EventCode::TuningCommitted;
  s.queue(makeEvent(s.now, ok ? EventLevel::Info : EventLevel::Warning, code, Reason::NONE, cmd.value, 0.0,
                    static_cast<int>(cmd.type)));
  return ok;
}

const Outputs& Regulator::step(const Inputs& in) noexcept {
  State& s = *s_;
  const Params& p = s.p;
  Outputs& out = s.out;
  EventBatch& ev = out.events;
  ev.clear();
  for (std::size_t i = 0; i < s.pendingCount; ++i) ev.push(s.pending[i]);
  s.pendingCount = 0;
  s.now = in.now;

  // 1. Auto-zero BEFORE the control step (it owns GPIO4 while active).
  s.bat.checkAutoZeroTriggers(in, ev);
  const bool autoZeroActive = s.bat.processAutoZero(in, ev);

  // 2. Corrected sensors and the CH1 record-path filters.
  const double MeasuredAmps =
      std::isfinite(in.altCurrentRaw.value) ? s.bat.correctedAltAmps(in.altCurrentRaw.value) : kNoValue;
  const double Bcur = std::isfinite(in.Bcur.value) ? s.bat.correctedBcur(in.Bcur.value) : kNoValue;
  const Reading& temp = alternatorTemperature(in, p.TempSource);
  ControlSensors cs;
  cs.now = in.now;
  cs.ch1Fresh = in.altCurrentRaw.fresh;
  cs.MeasuredAmps = MeasuredAmps;
  cs.IBV = in.IBV.value;
  cs.ibvFresh = in.IBV.fresh;
  cs.Bcur = Bcur;
  cs.rpm = in.rpm.value;
  cs.TempToUse = temp.value;
  cs.tempStamp = temp.stamp;
  cs.SOC_percent = s.bat.socPercent();
  cs.socKnown = s.bat.socKnown();
  s.law.updateFilters(cs, p);

  // 3. Protection detectors and sustained timers. A resting field (last
  // tick) quiets the tach: the RPM gate must know it is not a stopped engine.
  s.prot.setFieldResting(s.law.fieldResting());
  s.prot.updateDetectors(in, MeasuredAmps, ev);
  // Battery temperature (docs/batteries.md): cold/hot orders, current cap, and the
  // compensated targets the stage machine and the voltage loop see.
  const BatteryTempDecision& bt = s.batTemp.update(in, p, ev);
  cs.batteryChargeCapA = bt.currentCapA;
  const double compV = temperatureCompensationV(p, bt.tempC);
  const Params* stageParams = &p;
  if (compV != 0.0) {
    compensateTargets(p, compV, s.compensated);
    stageParams = &s.compensated;
  }

  // 4. The BMS's limits, then the charging stage (suppressed in override modes and manual).
  s.law.updateBms(in.bms, in.now, Bcur, in.IBV.value, p, ev);
  const bool manualMode = p.ManualMode || s.opManual;
  s.law.updateChargingStage(cs, *stageParams, manualMode, ev);

  // 5. Immutable snapshot and mode selection by priority.
  TickSnapshot snap;
  snap.now = in.now;
  snap.prot = s.prot.flags();
  snap.limpHome = s.limpHome;
  snap.manualMode = manualMode;
  snap.sysOff = s.opOff;
  snap.ignitionOn = in.ignitionOn;
  snap.OnOff = p.OnOff;
  snap.bmsChargeEnabled = in.bmsChargeEnabled && s.law.bms().chargeAllowed();
  // A floor the forecast does not get to argue with (docs/deviations.md
  // "Weather mode's SoC floor"): below it, or with the SoC unknown, charge.
  snap.weatherModeActive =
      p.weatherModeEnabled && s.currentWeatherMode && cs.socKnown && cs.SOC_percent >= p.WeatherModeMinSoC;
  // IDLE rests the field, unless the alternator carries the house loads
  // while the bank rests (IdleZeroCurrent).
  snap.idleStage = s.law.stages().inIdleStage() && !s.law.idleZeroCurrentHold(p);
  snap.batteryCold = bt.cold;
  snap.batteryHot = bt.hot;
  snap.autoZeroActive = autoZeroActive;
  const ModeDecision d = selectFieldMode(snap);

  // 6. Mode transitions: bumpless enter_sys_* and the mode-change event.
  if (s.firstTick || d.mode != s.lastMode) {
    switch (d.mode) {
      case FieldControlMode::MODE_NORMAL_AUTO_PID:
        s.law.enter_sys_auto(cs, p);
        if (!s.firstTick && isRampMode(s.lastMode)) s.law.onProtectionCleared(in.now);
        break;
      case FieldControlMode::MODE_NORMAL_MANUAL:
      case FieldControlMode::MODE_LIMP_HOME:
        s.law.enter_sys_manual();
        break;
      case FieldControlMode::MODE_DISABLED_RAMP:
        s.law.enter_sys_off();
        break;
      default:
        s.law.enter_sys_fault();
        break;
    }
    ev.push(makeEvent(in.now, isNormalMode(d.mode) ? EventLevel::Info : EventLevel::Warning,
                      EventCode::ModeChanged, d.reason, static_cast<double>(s.lastMode), 0.0, 0, d.mode));
  }
  s.firstTick = false;
  s.lastMode = d.mode;
  s.lastReason = d.reason;

  // 7. Shutdown path every tick (it tracks transitions), else normal control.
  const ShutdownCommand sc = s.prot.runShutdownPath(d, s.law.lastAppliedDuty(), s.law.rpmMinDuty(), ev);
  if (sc.applyImmediateCut) s.law.applyImmediateCut();
  double duty = 0.0;
  bool field = false;
  bool fastOvActive = false;
  GovMode govMode = GovMode::GOV_NORMAL_SLEW;
  if (sc.active) {
    duty = sc.dutyPct;  // already slewed by the phase rates (effective minimum 0)
    field = sc.fieldEnable;
    govMode = sc.govMode;
    s.law.trackShutdown(duty, p, cs.rpm);
  } else if (d.mode == FieldControlMode::MODE_LIMP_HOME) {
    duty = s.law.runLimpHome(cs, p, ev);
    field = true;
  } else if (d.mode == FieldControlMode::MODE_NORMAL_MANUAL) {
    duty = s.law.runManual(cs, p, s.opManual ? s.opManualDuty : p.ManualDutyTarget);
    field = true;
  } else if (d.mode == FieldControlMode::MODE_NORMAL_AUTO_PID) {
    const double uTargetRaw = s.law.computeUTarget(cs, p);
    FastOvInputs fi;
    fi.voltageControlActive = s.law.voltageControlActive();
    fi.floatStage = s.law.stages().inFloatStage();
    fi.ChargingVoltageTarget = s.law.ChargingVoltageTarget();
    fi.uTargetAmps = uTargetRaw;
    fi.setpointLimited = s.law.setpointLimited();
    fi.cv_I = s.law.cv_I();
    fi.MeasuredAmps = MeasuredAmps;
    fi.MeasuredAmps_filtered = s.law.MeasuredAmps_filtered();
    fi.altCurrentFresh = in.altCurrentRaw.fresh;
    const FastOvAction fa = s.prot.runFastOvSupervisors(fi);
    FastOvApply apply;
    apply.fastOvCurrentCap = fa.fastOvCurrentCap;
    apply.fastOvClampActive = fa.fastOvClampActive;
    apply.setCvI = fa.cvIAction != CvIAction::None;
    apply.cv_I = fa.cv_I;
    apply.zeroSetpointLimited = fa.zeroSetpointLimited;
    apply.forceBypassSlew = fa.forceBypassSlew;
    apply.sensorFailureBypass = snap.prot.voltageImplausible || snap.prot.voltageDisagreeCritical;
    duty = s.law.finishAuto(cs, p, apply, ev);
    field = !s.law.fieldResting();  // a full bank at the RPM floor rests the field
    fastOvActive = fa.fastOvClampActive;
    govMode = s.law.govMode();
  } else {
    // A non-normal mode the sequencer did not take: the safe state.
    duty = 0.0;
    field = false;
    s.law.trackShutdown(0.0, p, cs.rpm);
  }
  if (autoZeroActive) {
    // The auto-zero owns the field: LOW for the whole measurement.
    field = false;
    duty = 0.0;
    s.law.trackShutdown(0.0, p, cs.rpm);
  }
  if (!std::isfinite(duty)) {
    duty = 0.0;
    field = false;
  }

  // Field enable edges.
  if (field && !s.lastField) {
    s.law.onFieldTurnOn(in.now);
    ev.push(makeEvent(in.now, EventLevel::Info, EventCode::FieldOn, Reason::NONE, 0.0, 0.0, 0, d.mode));
  } else if (!field && s.lastField) {
    ev.push(makeEvent(in.now, EventLevel::Info, EventCode::FieldOff, d.reason, 0.0, 0.0, 0, d.mode));
  }
  s.lastField = field;

  out.dutyPct = field ? std::clamp(duty, 0.0, 100.0) : 0.0;
  out.fieldEnable = field;
  out.inaFastMode = field;  // fast conversions while the field is on (Group 1 dv/dt, ALERT speed)
  out.inaBovlVolts = voltageHardwareLimit(p);

  // 8. SoC and energy.
  s.bat.UpdateBatterySOC(in, MeasuredAmps, ev);
  if (s.law.stages().completedOnTail()) s.bat.chargeCompletedOnTail(in.now, ev);

  // 9. Alarms (250 ms cadence inside).
  s.prot.setBmsStale(s.law.bms().stale());
  out.buzzer = s.prot.checkAlarms(false, ev);

  // 10. Telemetry: this tick's inputs and decisions, then the modules'
  // state after the step.
  Telemetry& t = out.telemetry;
  t.now = in.now;
  t.mode = d.mode;
  // A stale BMS only caps the charge (no mode change): the reason still says so.
  t.reason = d.reason == Reason::NONE && s.law.bms().stale() ? Reason::REASON_BMS_STALE : d.reason;
  t.ibv_v = in.IBV.value;
  t.battery_v = in.BatteryV.value;
  t.bcur_a = Bcur;
  t.alt_a = MeasuredAmps;
  t.rpm = in.rpm.value;
  t.temp_f = temp.value;
  t.battery_temp_c = in.batteryTempC.value;
  t.duty_pct = out.dutyPct;
  t.field_enable = out.fieldEnable;
  t.ignition_on = in.ignitionOn;
  t.fast_ov_active = fastOvActive;
  t.alarm = out.buzzer;
  s.tickGovMode = govMode;
  fillStateTelemetry();
  return out;
}

// The telemetry that reads the modules' state after this step.
void Regulator::fillStateTelemetry() {
  State& s = *s_;
  Telemetry& t = s.out.telemetry;
  s.law.fillTelemetry(t.control);
  t.control.govMode = s.tickGovMode;
  t.control.limpHome = s.lastMode == FieldControlMode::MODE_LIMP_HOME;
  s.prot.fillTelemetry(t.protection);
  s.bat.updateTelemetry(t.battery);
  t.stage = s.law.stages().stage();
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
}

}  // namespace xr
