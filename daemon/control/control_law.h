#pragma once
// ControlLaw: the cascaded loops of docs/control.md as owned parts, and the
// coordinator that runs them in the command path's order. Regulator::step
// drives it; tests drive it directly. No protection or battery types here:
// the fast-OV supervisors' actions come in as a FastOvVerdict (core/), so the
// law is testable on its own.
//
// One AUTO tick, in the command path's order (docs/architecture.md "Control
// law and the step"):
//   updateFilters()   : InputFilters (every tick)
//   updateChargingStage(): VoltageTarget (stage machine, overrides)
//   computeUTarget()  : CurrentCommand: I_cap -> - thermal penalty -> clamp
//                       [0, MaxTableValue] -> MaximumAllowedBatteryAmps ->
//                       warm-up ceiling -> battery caps -> MaintainMode 0 /
//                       TuningMode wave => uTargetRaw
//   (Regulator runs the fast-OV supervisors on uTargetRaw)
//   finishAuto()      : FastOvEpisode + fast-OV cap => uTargetAmps, FieldRest
//                       end -> VoltageCvLoop (Icv) or direct => SetpointSlew
//                       => setpointLimited -> InnerLoop (PID, governor) ->
//                       FieldRest start.
#include "control/bms_limiter.h"
#include "control/command_caps.h"
#include "control/control_sensors.h"
#include "control/control_telemetry.h"
#include "control/current_command.h"
#include "control/cv_loop.h"
#include "control/fast_ov_episode.h"
#include "control/field_rest.h"
#include "control/inner_loop.h"
#include "control/input_filters.h"
#include "control/limp_home.h"
#include "control/setpoint_slew.h"
#include "control/system_id.h"
#include "control/tuning_mode.h"
#include "control/voltage_target.h"
#include "core/events.h"
#include "core/inputs.h"
#include "core/modes.h"
#include "params/params.h"

namespace xr {

class ControlLaw {
 public:
  explicit ControlLaw(const Params& p);

  // Every tick, first: filters on fresh CH1 / IBV, control dt bookkeeping.
  void updateFilters(const ControlSensors& s, const Params& p) noexcept { filters_.update(s, p); }
  // Before the charging stage: the BMS's limits of this tick (bms_limiter.h).
  void updateBms(const BmsLimits& b, TimeNs now, double Bcur, double packV, const Params& p,
                 EventBatch& ev) noexcept {
    bms_.update(b, now, Bcur, packV, p, ev);
  }
  // Step 3 (before mode selection): stage machine and override targets.
  void updateChargingStage(const ControlSensors& s, const Params& p, bool manualMode,
                           EventBatch& ev) noexcept;

  // ---- AUTO path -----------------------------------------------------------
  double computeUTarget(const ControlSensors& s, const Params& p) noexcept;  // returns uTargetRaw
  // Returns the applied duty (after governor). Holds the PID and the duty when
  // CH1 is not fresh (the protections' state actions still apply).
  double finishAuto(const ControlSensors& s, const Params& p, const FastOvVerdict& ov,
                    EventBatch& ev) noexcept;

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
  void onProtectionCleared(TimeNs now) noexcept { slew_.onProtectionCleared(now); }

  // ---- commands ----------------------------------------------------------
  bool startSystemId(TimeNs now, bool autoRunning) noexcept;
  bool commitTuning(TimeNs now, const Params& p) noexcept { return tuning_.commit(now, p); }
  bool commitCvTuning(TimeNs now, const Params& p) noexcept { return targets_.commitCvTuning(now, p); }

  // ---- read-back -----------------------------------------------------------
  SysMode sysMode() const noexcept { return sysMode_; }
  double lastAppliedDuty() const noexcept { return inner_.lastAppliedDuty(); }
  double rpmMinDuty() const noexcept { return inner_.rpmMinDuty(); }
  double setpointLimited() const noexcept { return slew_.setpointLimited(); }
  double uTargetAmps() const noexcept { return command_.uTargetAmps(); }
  double ChargingVoltageTarget() const noexcept { return targets_.ChargingVoltageTarget(); }
  bool voltageControlActive() const noexcept { return targets_.voltageControlActive(); }
  // Full bank at the RPM duty floor: the field rests (enable LOW) in AUTO
  // (docs/deviations.md "Full bank at light load").
  bool fieldResting() const noexcept { return rest_.resting(); }
  // IDLE with IdleZeroCurrent (voltage_target.h).
  bool idleZeroCurrentHold(const Params& p) const noexcept { return targets_.idleZeroCurrentHold(p); }
  // MaintainMode or the idle hold: the current loop chases Bcur = 0.
  bool holdsZeroBatteryCurrent(const Params& p) const noexcept {
    return p.MaintainMode || idleZeroCurrentHold(p);
  }
  double thermalPenaltyAmps() const noexcept { return command_.thermal().thermalPenaltyAmps(); }
  double MeasuredAmps_filtered() const noexcept { return filters_.input().value(); }
  double g_pidI_filtered() const noexcept { return filters_.pidFiltered().value(); }
  double cv_I() const noexcept { return cv_.cv_I(); }
  bool fastOvClampActive() const noexcept { return fastOv_.clampActive(); }
  bool systemIdRunning() const noexcept { return sysId_.systemIdRunning(); }
  const ChargingStageMachine& stages() const noexcept { return targets_.stages(); }
  const BmsLimiter& bms() const noexcept { return bms_; }
  const Pid& currentPID() const noexcept { return inner_.pid(); }
  const ThermalDerate& thermal() const noexcept { return command_.thermal(); }
  const TuningModeRunner& tuning() const noexcept { return tuning_; }
  const CvTuningModeRunner& cvTuning() const noexcept { return targets_.cvTuning(); }
  const SystemId& systemId() const noexcept { return sysId_; }
  bool bulkVoltageLimitActive() const noexcept { return targets_.bulkVoltageLimitActive(); }
  GovMode govMode() const noexcept { return inner_.govMode(); }
  double setpointCommand() const noexcept { return slew_.setpointCommand(); }
  void fillTelemetry(ControlTelemetry& t) const noexcept;
  // This tick's alternator-side caps (the command path's, computed only in AUTO).
  void fillCommandCaps(CommandCaps& c, const Params& p) const noexcept;

 private:
  // The field is "full" within this of MaxDuty (duty %).
  static constexpr double kFullFieldDutyBand = 1.0;

  void enterManualLike(SysMode m) noexcept;
  void leaveAuto(TimeNs now) noexcept;
  void fillLoopTelemetry(ControlTelemetry& t) const noexcept;
  void fillTuningTelemetry(ControlTelemetry& t) const noexcept;
  // TuningMode, CVTuningMode or a SystemID run: no rest starts or lasts.
  bool tuningActive(const Params& p) const noexcept;
  RestInputs restInputs(const ControlSensors& s, const Params& p) const noexcept;
  double holdAtRest() noexcept;
  void updateGovMode(const ControlSensors& s, const Params& p, const FastOvVerdict& ov) noexcept;
  // finishAuto's steps (control_law.cpp).
  void applyFastOv(const ControlSensors& s, const Params& p, const FastOvVerdict& ov) noexcept;
  double runSystemIdTick(const ControlSensors& s, const Params& p, EventBatch& ev) noexcept;
  double slewSetpoint(const ControlSensors& s, const Params& p, double dt) noexcept;
  double runInnerLoop(const ControlSensors& s, const Params& p, double dt) noexcept;

  // The parts, in the order one AUTO tick runs them.
  InputFilters filters_;     // feedback filters and the tick / control dts
  BmsLimiter bms_;           // the BMS's limits (CVL, CCL) and their staleness
  VoltageTarget targets_;    // stage machine and the voltage target / override modes
  TuningModeRunner tuning_;  // TuningMode's current wave and its score
  CurrentCommand command_;   // uTarget and its caps (RPM table, thermal, battery caps)
  FastOvEpisode fastOv_;     // the fast-OV episode: its cap, load-dump reseed, CV overshoot latch
  FieldRest rest_;           // the field rest of a full bank at the RPM floor
  VoltageCvLoop cv_;         // the voltage loop: Icv
  SetpointSlew slew_;        // setpointCommand -> setpointLimited
  InnerLoop inner_;          // the current PID and the governor: the duty
  SystemId sysId_;           // the plant-delay step test (pins the inner loop)
  LimpHome limp_;            // Limp Home's fixed duty
  SysMode sysMode_ = SysMode::SYS_MODE_OFF;  // the bumpless mode wrappers' mode
  TimeNs leftAutoAt_ = -1;                   // when sysMode_ last left AUTO (-1: never was in AUTO)
  double sysIdDutyOut_ = 0.0;                // the SystemID run's duty request (telemetry)
};

}  // namespace xr
