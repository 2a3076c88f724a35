#pragma once
// ProtectionSupervisor: owns ALL protection state of
// docs/protections.md (detectors, INA228 software latch, shutdown
// sequencer, cooldown lockout, fast-OV supervisors, alarm buzzer).
//
// Pure: no I/O, no clock (time comes from Inputs::now), no allocation after
// construction, no globals. One instance per Regulator.
//
// ---------------------------------------------------------------------------
// WHERE each method is called in Regulator::step (control engineer's side)
// ---------------------------------------------------------------------------
//   (a) compute MeasuredAmps (= altCurrentRaw - DynamicAltCurrentZero) and
//       MeasuredAmps_filtered as usual.
//   (b) prot.updateDetectors(in, MeasuredAmps, events)            // step 2
//   (c) update the charging stage                                  // step 3
//   (d) TickSnapshot snap; snap.now = in.now; snap.prot = prot.flags();
//       fill the operator fields (limpHome, manualMode, sysOff, ignitionOn,
//       OnOff, bmsChargeEnabled, weatherModeActive, idleStage,
//       autoZeroActive).                                           // step 1
//   (e) ModeDecision d = selectFieldMode(snap);   (mode_selection.h, pure)
//   (f) ShutdownCommand sc = prot.runShutdownPath(d, lastAppliedDuty,
//                                                  rpmMinDuty, events);
//       EVERY tick, normal modes included (it tracks transitions). The
//       caller emits the ModeChanged event on mode transitions; this does not.
//       - if sc.applyImmediateCut: run control's applyImmediateCut(): PWM 0,
//         currentPID reset (integrator -> 0, MANUAL), sysMode = SYS_MODE_FAULT,
//         setpointLimited = 0, abort any running SystemID. (GPIO4 LOW and the
//         shutdown phase are already in sc.)
//       - if sc.active: Outputs.dutyPct = sc.dutyPct, Outputs.fieldEnable =
//         sc.fieldEnable, lastAppliedDuty = sc.dutyPct, govMode = sc.govMode.
//         The duty is already slewed by the phase rates: do NOT run
//         governorApply() on it (effectiveMin is 0 in shutdown). Skip the
//         normal control path (PID tracks lastAppliedDuty as in MANUAL).
//       - if !sc.active: run the normal path (AUTO PID / MANUAL / Limp Home).
//         Outputs.fieldEnable may be true.
//   (g) In the AUTO path, after uTargetAmps is known and BEFORE the CV loop /
//       setpoint slew:
//         FastOvAction fa = prot.runFastOvSupervisors({...});
//       then:
//         uTargetAmps = min(uTargetAmps, fa.fastOvCurrentCap);
//         fastOvClampActive = fa.fastOvClampActive (CV anti-windup state 1/3,
//           SetpointFallRate -> 1e9 while set);
//         switch (fa.cvIAction): Snap/Bleed/Reseed -> cv_I = fa.cv_I;
//         if fa.zeroSetpointLimited: setpointLimited = 0 (load dump);
//         if fa.forceBypassSlew: govMode = GOV_BYPASS_SLEW for this tick.
//       In every other mode do not call it (its state decays by itself: the
//       next call after a gap starts clean).
//   (h) Outputs.buzzer = prot.checkAlarms(effAnomalyAlarmActive, events);
//       every tick; it evaluates on its own 250 ms cadence and holds between.
//   (i) telemetry.protection = prot.telemetry();
//       telemetry.fast_ov_active = fastOvClampActive;
//
// Commands (between ticks): CommandType::ReenableField -> prot.reenableField();
// CommandType::ResetAlarmLatch -> prot.resetAlarmLatch(). setParams() on every
// Regulator::setParams().
#include <algorithm>
#include <array>
#include <cstdint>

#include "core/events.h"
#include "core/inputs.h"
#include "core/modes.h"
#include "params/params.h"
#include "protection/alarm_rows.h"
#include "protection/mode_selection.h"
#include "protection/protection_telemetry.h"
#include "protection/tick_snapshot.h"

namespace xr {

// Result of runShutdownPath() for this tick.
struct ShutdownCommand {
  bool active = false;      // a non-normal mode owns the outputs this tick
  double dutyPct = 0.0;     // duty to apply (already slewed; 0..100)
  bool fieldEnable = true;  // GPIO4; false once cut
  GovMode govMode = GovMode::GOV_NORMAL_SLEW;
  double effectiveMin = 0.0;       // always 0 during shutdown (docs/control.md)
  bool applyImmediateCut = false;  // control must run its applyImmediateCut() resets
  ShutdownPhase phase = ShutdownPhase::PHASE_NONE;
  bool faultAlarm = false;  // critical/warning/lockout (not DISABLED): GPIO21 wants ON
};

// Control values the fast-OV supervisors read (AUTO path only).
struct FastOvInputs {
  bool voltageControlActive = false;
  bool floatStage = false;  // FLOAT arms the supervisors whatever its target
  double ChargingVoltageTarget = 0.0;
  double uTargetAmps = 0.0;            // fastOvBaseCap: the request before the fast-OV clamp
  double setpointLimited = 0.0;        // slewed setpoint of the previous tick
  double cv_I = 0.0;                   // CV integrator now
  double MeasuredAmps = 0.0;           // raw alternator current (A)
  double MeasuredAmps_filtered = 0.0;  // EMA(InputFilterTC)
  bool altCurrentFresh = false;        // a new CH1 sample this tick (feeds the MA window)
};

enum class CvIAction { None, Snap, Bleed, Reseed };

struct FastOvAction {
  bool nearBulk = false;
  double fastOvCurrentCap = 0.0;  // clamp uTargetAmps to this (== uTargetAmps when idle)
  bool fastOvClampActive = false;
  CvIAction cvIAction = CvIAction::None;
  double cv_I = 0.0;                 // new cv_I when cvIAction != None
  bool forceBypassSlew = false;      // govMode = GOV_BYPASS_SLEW this tick
  bool zeroSetpointLimited = false;  // load dump: setpointLimited = 0
  // Which supervisors acted (telemetry/tests).
  bool group1 = false, group2 = false, group3 = false, loadDump = false;
};

class ProtectionSupervisor {
 public:
  explicit ProtectionSupervisor(const Params& p);
  void setParams(const Params& p) noexcept;

  // Step 2: sustained timers and every detector. MeasuredAmps is the
  // zero-corrected alternator current (NaN when unknown). Also: INA228 latch
  // (250 ms cadence, release check 3 s, recheck 10 s), dv/dt EMA and
  // dBcur/dt on fresh INA samples, lockout expiry.
  void updateDetectors(const Inputs& in, double MeasuredAmps, EventBatch& ev) noexcept;
  // Control's field rest (AUTO, full bank) of the last tick: while it lasts,
  // and RPM_REST_GRACE_MS after, the RPM gate trusts the RPM seen before it.
  void setFieldResting(bool resting) noexcept { fieldResting_ = resting; }
  // The BMS limits went stale (BmsLimiter): an alarm row of its own.
  void setBmsStale(bool stale) noexcept { bmsStale_ = stale; }
  // The BMS's values do not fit the bank, and charging held for long
  // (docs/protections.md): rows whose own event tells the owner once.
  void setChargeChecks(bool bmsMismatch, bool chargingHeld) noexcept {
    bmsMismatch_ = bmsMismatch;
    chargingHeld_ = chargingHeld;
  }
  const ProtectionFlags& flags() const noexcept { return flags_; }

  // Step 7: the shutdown sequencer (three paths + lockout + disabled ramp).
  // Call every tick with this tick's decision.
  ShutdownCommand runShutdownPath(const ModeDecision& d, double lastAppliedDuty, double rpmMinDuty,
                                  EventBatch& ev) noexcept;

  // Groups 1/2/3 and load dump (AUTO path, see (g) above).
  FastOvAction runFastOvSupervisors(const FastOvInputs& x) noexcept;

  // CheckAlarms(): evaluates every 250 ms, returns the GPIO21 level.
  bool checkAlarms(bool effAnomalyAlarmActive, EventBatch& ev) noexcept;

  // Commands.
  void reenableField() noexcept;    // clears the T2 latch (and restarts its timer)
  void resetAlarmLatch() noexcept;  // ResetAlarmLatch
  // AcknowledgeAlarm: the buzzer goes quiet for the rows sounding now (and a
  // latch is released); the protections act on untouched. A row that was not
  // sounding starts it again; once every row is quiet the acknowledgement
  // ends, so the next alarm sounds (docs/protections.md "Acknowledging an alarm").
  void acknowledgeAlarm() noexcept;
  bool alarmAcknowledged() const noexcept { return ackActive_; }

  ProtectionTelemetry telemetry() const noexcept;
  // Same, written in place (Regulator::step fills its persistent Outputs
  // without building and copying a temporary every tick).
  void fillTelemetry(ProtectionTelemetry& t) const noexcept;

 private:
  struct TimerState {
    TimeNs since = -1;  // first instant the condition held, -1 = not holding
  };
  bool sustained(TimerState& t, bool cond, TimeNs hold) const noexcept;
  void updateInaLatch(const Inputs& in, EventBatch& ev) noexcept;
  void updateVoltageSensors(const Inputs& in, EventBatch& ev) noexcept;
  void updateBankMismatch(EventBatch& ev) noexcept;
  void updateRpmGate(EventBatch& ev) noexcept;
  void updateTemperature(const Inputs& in, EventBatch& ev) noexcept;
  void updateCurrent(const Inputs& in, double MeasuredAmps, EventBatch& ev) noexcept;
  void updateFastSamples(const Inputs& in) noexcept;
  // logTrip = false when a dedicated event (seed wording) already reports the trip.
  // Trip/clear logging memory of one detector. A detector sitting on its
  // threshold (noise, or a ramp that brings the value back to exactly the
  // limit) must not write a trip/clear pair every tick: the clear is logged
  // only after the condition stayed false for kEventClearHold.
  struct EventEdge {
    bool logged = false;
    TimeNs falseSince = -1;
  };
  static constexpr TimeNs kEventClearHold = 1'000'000'000;
  void edge(EventEdge& e, bool now, Reason r, double a, double b, EventBatch& ev,
            EventLevel level = EventLevel::Warning, bool logTrip = true) noexcept;
  void push(EventBatch& ev, EventCode c, EventLevel l, Reason r, double a = 0.0, double b = 0.0,
            int detail = 0) const noexcept;
  void startLockout(EventBatch& ev) noexcept;
  void resetFastOv() noexcept;
  // runShutdownPath's steps (shutdown_sequencer.cpp).
  void cutImmediately(Reason reason, double lastAppliedDuty, EventBatch& ev) noexcept;
  void latchRamp(const ModeDecision& d, bool faultRamp) noexcept;
  GovMode startRamp(FieldControlMode mode, double lastAppliedDuty) noexcept;
  void stepRampPhases(double floorDuty, bool faultRamp, Reason reason, EventBatch& ev) noexcept;
  // runFastOvSupervisors' steps (fast_ov.cpp).
  void pushGroup3Sample(const FastOvInputs& x) noexcept;
  double voltageGroupsCap(const FastOvInputs& x, FastOvAction& a) noexcept;
  double group3Signal(const FastOvInputs& x) const noexcept;
  double runGroup3(const FastOvInputs& x, bool loadDump, TimeNs prevCall, double base,
                   FastOvAction& a) noexcept;

  Params p_;
  ProtectionFlags flags_;
  TimeNs now_ = 0;
  TimeNs boot_ = -1;
  // The previous tick's now_: the sequencer's ramp step dtSec() is computed
  // from it only on the ticks that ramp, not on every tick.
  TimeNs prevNow_ = 0;
  double dtSec() const noexcept { return std::clamp(toSec(now_ - prevNow_), 0.0, 1.0); }

  // Latest values seen by the detectors (telemetry, alarms, accelerator).
  double IBV_ = kNoValue, BatteryV_ = kNoValue, Bcur_ = kNoValue, MeasuredAmps_ = kNoValue;
  double TempToUse_ = kNoValue;
  double rpm_ = kNoValue;
  bool fieldResting_ = false;
  bool bmsStale_ = false;
  bool bmsMismatch_ = false, chargingHeld_ = false;
  bool rpmOkAtRestStart_ = false;
  bool rpmEverRead_ = false;  // an engine speed was read since start
  TimeNs restEndedAt_ = -1;
  bool wasResting_ = false;
  bool inaFastModeActive_ = false;
  TimeNs inaFastSince_ = -1;   // when the INA228 last entered fast mode (stale window)
  bool tempStaleRaw_ = false;  // "no valid read > 20 s" for the buzzer

  // INA228 software latch.
  TimeNs inaLatchedAt_ = 0;
  TimeNs inaNextRelease_ = 0;
  TimeNs inaClearedAt_ = -1;

  // Sustained timers.
  TimerState disagreeWarnT_, disagreeCritT_, hardOcT_, t1T_, bankMismatchT_;
  // Edge memories for trip/clear events.
  EventEdge evBank_, evHardOc_, evT3_, evT1_, evRpm_, evAltHs_, evDisW_, evDisC_, evImpl_, evT5_, evCur_,
      evT4_, evSoak_;

  // Shutdown sequencer.
  FieldControlMode lastMode_ = FieldControlMode::MODE_DISABLED_RAMP;
  Reason lastReason_ = Reason::NONE;
  bool firstSequencerTick_ = true;
  ShutdownPhase phase_ = ShutdownPhase::PHASE_NONE;
  TimeNs phaseStart_ = 0;
  double duty_ = 0.0;
  double phase1Target_ = 0.0;
  bool fieldCut_ = true;  // GPIO4 starts LOW at boot
  TimeNs lockoutUntil_ = 0;
  bool shutdownRan_ = false;  // a ramp of the current episode reached its cut

  // Fast-OV supervisors.
  double dvdt_ = 0.0;
  double lastIbvSample_ = kNoValue;
  TimeNs lastIbvStamp_ = 0;
  double lastBcurSample_ = kNoValue;
  TimeNs lastBcurStamp_ = 0;
  double dBcurDt_ = 0.0;
  bool dBcurValid_ = false;
  int ldCount1_ = 0, ldCount2_ = 0, ldCount3_ = 0;
  bool loadDumpFiredThisSample_ = false;
  std::array<double, 64> maBuf_{};
  int maCount_ = 0, maHead_ = 0;
  int iexCount_ = 0;
  bool iexActive_ = false;
  double preEventCvI_ = 0.0;
  bool postFastOvGate_ = false;
  bool fastOvWasActive_ = false;
  double fastOvCap_ = 0.0;
  bool govBypassLatched_ = false;
  TimeNs lastFastOvCall_ = -1;
  double Vpred_ = 0.0;
  FastOvAction lastFastOv_;

  // CheckAlarms.
  TimeNs nextAlarmCheck_ = 0;
  bool buzzer_ = false;
  bool alarmLatched_ = false;
  bool faultAlarm_ = false;
  std::array<TimeNs, kAlarmRowCount> alarmMsgAt_{};
  std::array<bool, kAlarmRowCount> alarmRowOn_{};
  bool lastBuzzerEvent_ = false;
  bool ackActive_ = false;                         // acknowledged from the dashboard
  std::array<bool, kAlarmRowCount> ackRows_{};     // the rows that were sounding then
  TimeNs ackQuietSince_ = -1;                      // every row quiet since
  void updateAcknowledgement(bool cond) noexcept;  // CheckAlarms' acknowledgement step
  TimeNs buzzerOffSince_ = -1;                     // buzzer off since (AlarmOff logging hold)

  Reason lastTripReason_ = Reason::NONE;
  TimeNs lastTripTime_ = 0;
};

}  // namespace xr
