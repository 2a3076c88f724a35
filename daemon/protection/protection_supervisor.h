#pragma once
// ProtectionSupervisor: the coordinator of every protection of
// docs/protections.md. It holds the parts, each owning its own state, and
// calls them in the order of docs/architecture.md "Protection supervisor":
// the detectors (InaLatch, VoltageChecks, BankMismatchCheck, RpmGate,
// TemperatureChecks, CurrentChecks, the fast samples), the
// ShutdownSequencer, the FastOvSupervisor and the AlarmPanel.
//
// Pure: no I/O, no clock (time comes from Inputs::now), no allocation after
// construction, no globals. One instance per Regulator.
//
// Where each method is called in Regulator::step:
//   (a) updateDetectors(in, MeasuredAmps, events)  -- step 2, every tick
//   (b) TickSnapshot snap; snap.prot = flags(); ... selectFieldMode(snap)
//   (c) runShutdownPath(d, lastAppliedDuty, rpmMinDuty, events) -- every
//       tick, normal modes included (it tracks transitions). If
//       sc.applyImmediateCut: control's applyImmediateCut(). If sc.active
//       the sequencer owns duty, GPIO4 and govMode (already slewed by the
//       phase rates: no governor on it); else the normal path runs.
//   (d) AUTO path only, after the current request is known and before the
//       CV loop / setpoint slew: runFastOvSupervisors(FastOvInputs) returns
//       the FastOvAction whose verdict the control law applies (cap, cv_I
//       action, setpoint zero on a load dump, slew bypass). Other modes do
//       not call it (a gap starts it clean).
//   (e) checkAlarms(effAnomalyAlarmActive, events) -- every tick; the
//       GPIO21 level (250 ms cadence inside).
//   (f) fillTelemetry(t.protection).
// Commands (between ticks): reenableField(), resetAlarmLatch(),
// acknowledgeAlarm(); setParams() on every Regulator::setParams().
#include "core/events.h"
#include "core/inputs.h"
#include "core/modes.h"
#include "params/params.h"
#include "protection/alarms.h"
#include "protection/bank_mismatch.h"
#include "protection/current_checks.h"
#include "protection/fast_ov.h"
#include "protection/ina_latch.h"
#include "protection/mode_selection.h"
#include "protection/protection_log.h"
#include "protection/protection_telemetry.h"
#include "protection/rpm_gate.h"
#include "protection/shutdown_sequencer.h"
#include "protection/temperature_checks.h"
#include "protection/tick_snapshot.h"
#include "protection/voltage_checks.h"

namespace xr {

class ProtectionSupervisor {
 public:
  explicit ProtectionSupervisor(const Params& p);
  void setParams(const Params& p) noexcept;

  // Step 2: every detector, in order, then the lockout's expiry. MeasuredAmps
  // is the zero-corrected alternator current (NaN when unknown).
  void updateDetectors(const Inputs& in, double MeasuredAmps, EventBatch& ev) noexcept;
  // Control's field rest (AUTO, full bank) of the last tick: while it lasts,
  // and RPM_REST_GRACE_MS after, the RPM gate trusts the RPM seen before it.
  void setFieldResting(bool resting) noexcept { fieldResting_ = resting; }
  // The BMS limits went stale (BmsLimiter): an alarm row of its own.
  void setBmsStale(bool stale) noexcept { alarms_.setBmsStale(stale); }
  // The BMS's values do not fit the bank, and charging held for long
  // (docs/protections.md): rows whose own event tells the owner once.
  void setChargeChecks(bool bmsMismatch, bool chargingHeld) noexcept {
    alarms_.setChargeChecks(bmsMismatch, chargingHeld);
  }
  const ProtectionFlags& flags() const noexcept { return flags_; }

  // Step 7: the shutdown sequencer. Call every tick with this tick's decision.
  ShutdownCommand runShutdownPath(const ModeDecision& d, double lastAppliedDuty, double rpmMinDuty,
                                  EventBatch& ev) noexcept;

  // Groups 1/2/3 and load dump (AUTO path, see (d) above).
  FastOvAction runFastOvSupervisors(const FastOvInputs& x) noexcept { return fastOv_.update(x, p_); }

  // CheckAlarms(): evaluates every 250 ms, returns the GPIO21 level.
  bool checkAlarms(bool effAnomalyAlarmActive, EventBatch& ev) noexcept;

  // Commands.
  void reenableField() noexcept;  // clears the T2 latch (and restarts its timer)
  void resetAlarmLatch() noexcept { alarms_.resetLatch(); }
  // AcknowledgeAlarm (docs/protections.md "Acknowledging an alarm").
  void acknowledgeAlarm() noexcept { alarms_.acknowledge(now_); }
  bool alarmAcknowledged() const noexcept { return alarms_.acknowledged(); }

  ProtectionTelemetry telemetry() const noexcept;
  // Same, written in place (Regulator::step fills its persistent Outputs
  // without building and copying a temporary every tick).
  void fillTelemetry(ProtectionTelemetry& t) const noexcept;

 private:
  // The sensor values the detectors saw this tick (the alarm rows read them).
  struct Seen {
    double IBV = kNoValue, Bcur = kNoValue, MeasuredAmps = kNoValue;
  };
  ProtectionLog log(EventBatch& ev, FieldControlMode mode) noexcept { return {ev, now_, mode, lastTrip_}; }
  void publishFlags() noexcept;

  Params p_;                     // the parameters every part reads
  ProtectionFlags flags_;        // what mode selection reads: published from the parts
  TimeNs now_ = 0;               // this tick's time
  TimeNs prevNow_ = 0;           // the previous tick's (the sequencer's ramp step)
  TimeNs boot_ = -1;             // the first tick, -1 = none yet (grace periods)
  LastTrip lastTrip_;            // the last protection that tripped (telemetry)
  Seen seen_;                    // this tick's sensor values
  bool fieldResting_ = false;    // control's field rest of the last tick (RpmGate's input)
  InaLatch ina_;                 // INA228 ALERT software latch
  VoltageChecks voltage_;        // hard shutdown, disagreement, implausibility
  BankMismatchCheck bank_;       // bank size check
  RpmGate rpm_;                  // RPM gate
  TemperatureChecks temp_;       // T1 to T5, heat soak
  CurrentChecks current_;        // hard overcurrent, current stale
  FastOvSupervisor fastOv_;      // Groups 1/2/3, load dump, their sample rates
  ShutdownSequencer sequencer_;  // the three shutdown paths, lockout
  AlarmPanel alarms_;            // CheckAlarms, latch, acknowledgement
};

}  // namespace xr
