#pragma once
// ControlLaw: the cascaded loops of docs/control.md and their state, as
// plain members (the seeds' globals). Regulator::step drives it; tests drive
// it directly. No protection or battery types here: the fast-OV supervisors'
// actions come in as a FastOvApply, so the law is testable on its own.
//
// One AUTO tick, in the seed's command-path order:
//   computeUTarget()  : I_cap -> - thermalPenaltyAmps -> clamp [0, MaxTableValue]
//                       -> MaximumAllowedBatteryAmps -> warm-up ceiling
//                       -> MaintainMode 0 / TuningMode wave   => uTargetRaw
//   (Regulator runs the fast-OV supervisors on uTargetRaw)
//   finishAuto()      : fastOvCurrentCap clamp => uTargetAmps -> CV (Icv) or
//                       direct => setpointCommand -> slew => setpointLimited ->
//                       currentPID -> governorApply -> trackAppliedOutput.
#include "control/bms_limiter.h"
#include "control/charging_stage.h"
#include "control/command_caps.h"
#include "control/control_telemetry.h"
#include "control/cv_loop.h"
#include "control/cv_tuning_mode.h"
#include "control/feedback_filters.h"
#include "control/governor.h"
#include "control/limp_home.h"
#include "control/pid.h"
#include "control/system_id.h"
#include "control/thermal_derate.h"
#include "control/tuning_mode.h"
#include "core/events.h"
#include "core/inputs.h"
#include "core/modes.h"
#include "params/params.h"

namespace xr {

// Sensor values of this tick, already corrected (auto-zero, shunt gain).
struct ControlSensors {
  TimeNs now = 0;
  bool ch1Fresh = false;           // control work fires on fresh CH1
  double MeasuredAmps = kNoValue;  // CH1 - DynamicAltCurrentZero
  double IBV = kNoValue;
  bool ibvFresh = false;
  double Bcur = kNoValue;  // INA228 x DynamicShuntGainFactor (never Victron: MaintainMode)
  double rpm = kNoValue;
  double TempToUse = kNoValue;  // per TempSource
  TimeNs tempStamp = 0;
  double SOC_percent = kNoValue;
  bool socKnown = true;  // false while the battery monitor's SoC is only a guess (no SOC gating then)
  // Battery temperature current cap (cold ramp, no temperature).
  double batteryChargeCapA = 1e300;
};

// What the fast-OV supervisors (Groups 1/2/3, load dump) decided this tick.
struct FastOvApply {
  double fastOvCurrentCap = 1e300;  // clamp on uTargetAmps
  bool fastOvClampActive = false;
  bool setCvI = false;  // Snap / Bleed / Reseed
  double cv_I = 0.0;
  bool zeroSetpointLimited = false;  // load dump
  bool forceBypassSlew = false;
  bool sensorFailureBypass = false;  // !voltagePlausible || voltageDisagreementCritical
};

class ControlLaw {
 public:
  explicit ControlLaw(const Params& p);

  // Every tick, first: filters on fresh CH1 / IBV, control dt bookkeeping.
  void updateFilters(const ControlSensors& s, const Params& p) noexcept;
  // Before the charging stage: the BMS's limits of this tick (bms_limiter.h).
  void updateBms(const BmsLimits& b, TimeNs now, double Bcur, double packV, const Params& p,
                 EventBatch& ev) noexcept {
    bms_.update(b, now, Bcur, packV, p, ev);
  }
  // Step 3 (before mode selection): stage machine and override targets.
  // Returns true when the stage changed (event pushed).
  void updateChargingStage(const ControlSensors& s, const Params& p, bool manualMode,
                           EventBatch& ev) noexcept;

  // ---- AUTO path -----------------------------------------------------------
  double computeUTarget(const ControlSensors& s, const Params& p) noexcept;  // returns uTargetRaw
  // Returns the applied duty (after governor). Holds the PID and the duty when
  // CH1 is not fresh (the protections' state actions still apply).
  double finishAuto(const ControlSensors& s, const Params& p, const FastOvApply& fa, EventBatch& ev) noexcept;

  // ---- MANUAL / Limp Home / shutdown --------------------------------------
  double runManual(const ControlSensors& s, const Params& p, double manualDuty) noexcept;
  double runLimpHome(const ControlSensors& s, const Params& p, EventBatch& ev) noexcept;
  // The sequencer owns the duty: track it bumplessly (PID in MANUAL).
  void trackShutdown(double appliedDuty, const Params& p, double rpm) noexcept;

  // ---- mode entry (bumpless wrappers) --------------------------------------
  void enterSysOff() noexcept;
  void enterSysManual() noexcept;
  void enterSysAuto(const ControlSensors& s, const Params& p) noexcept;
  void enterSysFault() noexcept;
  // Control-side effects of the universal immediate cut (protection decides).
  void applyImmediateCut() noexcept;
  // Field enable rising edge: startup ramp and warm-up ceiling start now.
  void onFieldTurnOn(TimeNs now) noexcept;
  // A protection cleared: opens the FastSetpointRiseRate window.
  void onProtectionCleared(TimeNs now) noexcept {
    protectionClearedAt_ = now;
    haveProtectionCleared_ = true;
  }

  // ---- commands ----------------------------------------------------------
  bool startSystemId(TimeNs now, bool autoRunning) noexcept;
  bool commitTuning(TimeNs now, const Params& p) noexcept { return tuning_.commit(now, p); }
  bool commitCvTuning(TimeNs now, const Params& p) noexcept { return cvTuning_.commit(now, p); }

  // ---- read-back -----------------------------------------------------------
  SysMode sysMode() const noexcept { return sysMode_; }
  double lastAppliedDuty() const noexcept { return lastAppliedDuty_; }
  double rpmMinDuty() const noexcept { return rpmMinDuty_; }
  double setpointLimited() const noexcept { return setpointLimited_; }
  double uTargetAmps() const noexcept { return uTargetAmps_; }
  double ChargingVoltageTarget() const noexcept { return ChargingVoltageTarget_; }
  bool voltageControlActive() const noexcept { return voltageControlActive_; }
  // Full bank at the RPM duty floor: the field rests (enable LOW) in AUTO
  // (docs/deviations.md "Full bank at light load").
  bool fieldResting() const noexcept { return fieldResting_; }
  // IDLE with IdleZeroCurrent: the bank rests while the alternator carries
  // the house loads (docs/batteries.md "After absorption"). Not an override:
  // the stage machine keeps its re-bulk watch.
  bool idleZeroCurrentHold(const Params& p) const noexcept {
    return p.IdleZeroCurrent && stages_.inIdleStage() && !p.MaintainMode && !p.TargetVoltageMode &&
           !p.CVTuningMode;
  }
  // MaintainMode or the idle hold: the current loop chases Bcur = 0.
  bool holdsZeroBatteryCurrent(const Params& p) const noexcept {
    return p.MaintainMode || idleZeroCurrentHold(p);
  }
  double thermalPenaltyAmps() const noexcept { return thermal_.thermalPenaltyAmps(); }
  double MeasuredAmps_filtered() const noexcept { return emaInput_.value(); }
  double g_pidI_filtered() const noexcept { return emaPid_.value(); }
  double cv_I() const noexcept { return cv_.cv_I(); }
  bool fastOvClampActive() const noexcept { return fastOvClampActive_; }
  bool systemIdRunning() const noexcept { return sysId_.systemIdRunning(); }
  const ChargingStageMachine& stages() const noexcept { return stages_; }
  const BmsLimiter& bms() const noexcept { return bms_; }
  const Pid& currentPID() const noexcept { return currentPID_; }
  const ThermalDerate& thermal() const noexcept { return thermal_; }
  const TuningModeRunner& tuning() const noexcept { return tuning_; }
  const CvTuningModeRunner& cvTuning() const noexcept { return cvTuning_; }
  const SystemId& systemId() const noexcept { return sysId_; }
  bool bulkVoltageLimitActive() const noexcept { return bulkVoltageLimitActive_; }
  GovMode govMode() const noexcept { return govMode_; }
  double dutyRequest() const noexcept { return dutyRequest_; }
  double setpointCommand() const noexcept { return setpointCommand_; }
  void fillTelemetry(ControlTelemetry& t) const noexcept;
  // This tick's alternator-side caps (the command path's, computed only in AUTO).
  void fillCommandCaps(CommandCaps& c, const Params& p) const noexcept;

 private:
  // A control dt longer than this is not integrated as-is: such a gap means
  // the sensor stalled (current-stale protection acts on it); integrating it
  // would kick every loop.
  static constexpr double kMaxControlDtSec = 0.25;
  static constexpr double kNoCeiling = 1e300;
  // The CV loop is "at its ceiling" when its command is within this of it.
  static constexpr double kTailHeadroomA = 1.0;
  // The voltage loop "asks for no current" at or under this command.
  static constexpr double kRestNoCurrentA = 0.05;
  // The field is "full" within this of MaxDuty (duty %).
  static constexpr double kFullFieldDutyBand = 1.0;
  // A BMS alternator cap falling more than this between control ticks is a
  // step (snap the duty); slower falls are followed by the PID.
  static constexpr double kBmsSnapStepA = 3.0;

  void configurePid(const Params& p) noexcept;
  double governorStep(const Params& p, double request, GovMode mode, double dt) noexcept;
  void enterManualLike(SysMode m) noexcept;
  void leaveAuto(TimeNs now) noexcept;
  void fillLoopTelemetry(ControlTelemetry& t) const noexcept;
  void fillTuningTelemetry(ControlTelemetry& t) const noexcept;
  // Field rest (field_rest.cpp): when to start and end one, and the loops'
  // state while it lasts.
  bool restDue(const ControlSensors& s, const Params& p) noexcept;
  void applyTargetOverrides(const ControlSensors& s, const Params& p, bool overrideNow) noexcept;
  // TuningMode, CVTuningMode or a SystemID run: no rest starts or lasts.
  bool tuningActive(const Params& p) const noexcept;
  bool restOver(const ControlSensors& s, const Params& p) const noexcept;
  double holdAtRest() noexcept;
  void updateGovMode(const ControlSensors& s, const Params& p, const FastOvApply& fa) noexcept;
  void reseedAfterLoadDump(const ControlSensors& s) noexcept;
  // finishAuto's steps (control_law.cpp).
  void applyFastOv(const ControlSensors& s, const Params& p, const FastOvApply& fa) noexcept;
  double runSystemIdTick(const ControlSensors& s, const Params& p, EventBatch& ev) noexcept;
  double slewSetpoint(const ControlSensors& s, const Params& p, double dt) noexcept;
  void runCurrentPid(const ControlSensors& s, const Params& p, double dt) noexcept;
  double nonThermalCeiling(const Params& p, const FastOvApply& fa, double duty, double Icv) const noexcept;

  // Loops.
  Pid currentPID_;
  VoltageCvLoop cv_;
  ThermalDerate thermal_;
  ChargingStageMachine stages_;
  TuningModeRunner tuning_;
  CvTuningModeRunner cvTuning_;
  SystemId sysId_;
  LimpHome limp_;
  BmsLimiter bms_;

  // Filters (CH1 record path).
  Ema emaInput_, emaPid_, emaIBV_;
  // Battery current over seconds: what the bank accepted before a load dump.
  Ema emaBcur_;
  static constexpr double kBcurSlowTcMs = 2000.0;
  MovingAverage<64> maPid_;
  double MeasuredAmps_ = 0.0;
  double pidSig_ = 0.0;

  // Timing.
  TimeNs lastControlTick_ = -1, lastTick_ = -1;
  double controlDt_ = 0.0, tickDt_ = 0.0;
  TimeNs lastPidCompute_ = -1;
  int pidSampleCounter_ = 0;
  TimeNs lastTempStamp_ = 0;
  TimeNs lastFilterIbvNs_ = -1;

  // Command path state (the seeds' globals).
  SysMode sysMode_ = SysMode::SYS_MODE_OFF;
  GovMode govMode_ = GovMode::GOV_NORMAL_SLEW;
  double I_cap_ = 0.0, I_cmd_ = 0.0, uTargetRaw_ = 0.0, uTargetAmps_ = 0.0, nonThermalCeiling_ = 0.0;
  double setpointCommand_ = 0.0, setpointLimited_ = 0.0;
  double dutyRequest_ = 0.0, lastAppliedDuty_ = 0.0, rpmMinDuty_ = 0.0;
  bool voltageControlActive_ = false;
  double ChargingVoltageTarget_ = 0.0;
  bool inStartupRamp_ = false;
  TimeNs fieldOnAt_ = -1;
  TimeNs protectionClearedAt_ = 0;
  bool haveProtectionCleared_ = false;
  bool fastOvClampActive_ = false, fastOvWasActive_ = false;
  bool loadDumpInEpisode_ = false;  // a load dump acted since the fast-OV clamp engaged
  double dumpAcceptA_ = kNoValue;   // emaBcur_ when this episode's load dump first acted
  bool cvOvershootBypass_ = false;
  bool fastRiseActive_ = false;
  bool warmupActive_ = false;
  bool bulkVoltageLimitActive_ = false;
  bool overrideWasActive_ = false;
  TimeNs overrideSince_ = -1;
  TimeNs leftAutoAt_ = -1;  // when sysMode_ last left AUTO (-1: never was in AUTO)
  bool fieldResting_ = false;
  bool bmsCapActive_ = false;  // the BMS's battery-current cap binds the command this tick
  double bmsAltCap_ = kNoCeiling;
  double bmsAltCapPrev_ = kNoCeiling;  // at the last fresh CH1 (the snap compares)
  TimeNs restArmedAt_ = -1;            // the rest condition holds since (-1: not holding)
  double ibvSlope_ = 0.0;              // cvDSlope: dV/dt of IBV_filtered between fresh IBV samples
  double lastFiltV_ = 0.0;
  double sysIdDutyOut_ = 0.0;
  double fastOvCapA_ = kNoCeiling;  // the fast-OV supervisors' cap this tick
};

}  // namespace xr
