#pragma once
// BatteryMonitor: the battery's coordinator (docs/batteries.md,
// docs/architecture.md "Battery monitor"). It holds the parts that each own
// their state (auto-zero, SoC counter, shunt gain, rest re-anchor, health,
// energy, averages), picks the battery's voltage and current for them each
// tick, and calls them in a fixed order. Pure core: no I/O, no clock, no
// allocation after construction; time comes from Inputs::now.
//
// How Regulator::step must call it, every tick, in this order:
//
//   1. mon.checkAutoZeroTriggers(in, events);   // BEFORE the control step
//      const bool autoZeroActive = mon.processAutoZero(in, events);
//      If autoZeroActive: mode = MODE_LOCKOUT_RAMP, fieldEnable = LOW,
//      duty = MinDuty for this tick; the normal control path must not run
//      (the specification's "Critical ordering note").
//   2. const double MeasuredAmps = mon.correctedAltAmps(in.altCurrentRaw.value);
//      const double Bcur = mon.correctedBcur(in.Bcur.value);
//      Use these everywhere the specification uses MeasuredAmps / Bcur (the
//      control loop's MaintainMode path uses Bcur, never getBatteryCurrent()).
//   3. (control + protections step)
//   4. mon.updateBatterySoc(in, MeasuredAmps, events);   // every tick; it
//      integrates every tick, closes a SoC interval each SOCUpdateInterval
//      and predicts the charge times each INA_SLOW_INTERVAL_MS.
//   5. mon.updateTelemetry(outputs.telemetry.battery);
//
// Between ticks (command()): resetSocGain(), resetAltZero(), setSoc(pct).
// setParams() whenever Params are replaced. ledger()/restoreLedger() for the
// store (restoreLedger before the first step, or between ticks).
#include <cstdint>

#include "battery/battery_auto_zero.h"
#include "battery/battery_averages.h"
#include "battery/battery_health.h"
#include "battery/battery_ocv.h"
#include "battery/battery_telemetry.h"
#include "battery/energy_counter.h"
#include "battery/ledger.h"
#include "battery/shunt_gain.h"
#include "battery/soc_counter.h"
#include "core/events.h"
#include "core/inputs.h"
#include "core/time.h"
#include "params/params.h"

namespace xr {

namespace battery_k {
// INA228 current older than this is treated as absent (no integration).
inline constexpr std::int64_t INA_STALE_FOR_SOC_MS = 2000;
// Solar PPV older than this is not integrated.
inline constexpr std::int64_t SOLAR_STALE_MS = 10000;
}  // namespace battery_k

class BatteryMonitor {
 public:
  explicit BatteryMonitor(const Params& p);
  void setParams(const Params& p) noexcept;

  // ---- auto-zero (before the control step): AltCurrentAutoZero ------------
  void checkAutoZeroTriggers(const Inputs& in, EventBatch& ev) noexcept;
  // True while the field-off window runs (the caller forces
  // MODE_LOCKOUT_RAMP, field LOW, duty MinDuty).
  bool processAutoZero(const Inputs& in,
                       EventBatch& ev) noexcept {  // inline idle path: no call on almost every tick
    return autoZero_.active() && processActiveAutoZero(in, ev);
  }
  bool autoZeroActive() const noexcept { return autoZero_.active(); }

  // ---- corrected sensor values ---------------------------------------------
  double correctedAltAmps(double rawAmps) const noexcept { return autoZero_.corrected(rawAmps); }
  double correctedBcur(double raw) const noexcept { return gain_.corrected(raw); }
  // IBV (INA228 bus voltage) always.
  double getBatteryVoltage(const Inputs& in) const noexcept;
  // INA228 Bcur x gain, or VictronCurrent when BatteryCurrentSource == 3 and
  // its sample is no older than VICTRON_STALE_MS (else falls back to INA228).
  double getBatteryCurrent(const Inputs& in) const noexcept;
  bool usingVictronCurrent(const Inputs& in) const noexcept;

  // ---- SoC and energy (after the control step, every tick) -----------------
  // measuredAltAmps = correctedAltAmps(raw CH1).
  void updateBatterySoc(const Inputs& in, double measuredAltAmps, EventBatch& ev) noexcept;

  // ---- commands (between ticks) --------------------------------------------
  void resetSocGain() noexcept;      // DynamicShuntGainFactor = 1.0
  void resetAltZero() noexcept;      // DynamicAltCurrentZero = 0
  bool setSoc(double pct) noexcept;  // false (unchanged) when pct is outside 0..100 or NaN

  // ---- persistence ---------------------------------------------------------
  BatteryLedger ledger() const noexcept;
  // Restores lifetime state; implausible values (NaN, negative energies, gain
  // outside its bounds, count outside 0..capacity) are clamped or reset.
  void restoreLedger(const BatteryLedger& l) noexcept;

  // ---- outputs -------------------------------------------------------------
  void fillTelemetry(BatteryTelemetry& t) const noexcept;
  // Per-tick telemetry for a struct that lives from tick to tick and that
  // only this call writes (Regulator's Outputs): nearly every field changes
  // only when a SoC interval closes, the charge-time prediction, an
  // auto-zero, a command, setParams or restoreLedger runs, so the whole
  // struct is refilled only then; otherwise only the per-tick fields are
  // written. The result is always equal to fillTelemetry() (battery_test checks it).
  void updateTelemetry(BatteryTelemetry& t) noexcept;
  double socPercent() const noexcept {
    return soc_.percent(p_.BatteryCapacity_Ah);
  }  // read several times per tick
  // False while the SoC is the constructor's guess: no valid ledger restored,
  // no setSoc, no full-charge detection yet. Control may ignore SOC gating
  // (StageInputs::socValid) while this is false.
  bool socKnown() const noexcept { return socSource() == SocSource::Counted; }
  SocSource socSource() const noexcept { return soc_.source(); }
  bool fullChargeDetected() const noexcept { return soc_.fullDetected(); }
  // The charging stage ended absorption on its tail current: the bank is
  // full, a detected full charge like the monitor's own (its voltage and
  // tail thresholds may differ from the stage's, and a bank that rests
  // after absorption never meets them again; docs/batteries.md).
  void chargeCompletedOnTail(TimeNs now, EventBatch& ev) noexcept;
  double chargedEnergyLifetimeWh() const noexcept { return energy_.charged().lifetime(); }
  double alternatorChargedEnergyLifetimeWh() const noexcept { return energy_.alternator().lifetime(); }
  // Last shunt-gain correction outcome (tests, diagnostics).
  GainGuard lastGainGuard() const noexcept { return gain_.lastGuard(); }

  // SocCounter::peukertFactor (public for tests).
  static double peukertFactor(double dischargeCurrent_A, double capacity_Ah, double ratedCurrent_A,
                              double exponent) noexcept {
    return SocCounter::peukertFactor(dischargeCurrent_A, capacity_Ah, ratedCurrent_A, exponent);
  }

 private:
  bool processActiveAutoZero(const Inputs& in, EventBatch& ev) noexcept;
  AutoZeroInput autoZeroInput(const Inputs& in) const noexcept;
  void startTimers(TimeNs now) noexcept;
  // battery_monitor_tick.cpp: one SoC interval, a full charge, the rest
  // re-anchor and the health figures.
  void closeSocInterval(TimeNs now, double elapsed_s, EventBatch& ev) noexcept;
  void declareFullCharge(TimeNs now, EventBatch& ev) noexcept;
  void capacityPoint(TimeNs now, double socPct, bool full, EventBatch& ev) noexcept;
  void trackRest(const Inputs& in, double dt_s, double amps, double volts, double altAmps) noexcept;

  Params p_;                    // the running set (capacity, thresholds, features)
  bool telemetryStale_ = true;  // a slow telemetry field changed since updateTelemetry()
  bool started_ = false;        // the first tick has set the timers below
  TimeNs lastTick_ = 0;         // the previous updateBatterySoc: dt of the zero-order hold
  TimeNs lastSocUpdate_ = 0;    // the last SoC interval's end (SOCUpdateInterval)
  TimeNs lastChargeTimes_ = 0;  // the last charge-time prediction (INA_SLOW_INTERVAL_MS)
  // The latest battery sample the SoC interval and the telemetry use.
  double lastValidVoltage_ = 0.0;      // the last measured voltage (held while absent)
  double batteryCurrentForSoC_ = 0.0;  // the current counted this tick (0 when absent)
  bool usingVictron_ = false;          // that current came from VE.Direct
  bool socInputsValid_ = false;        // both current and voltage were measured this tick
  int nominalVoltage_ = 12;  // the bank class from the voltage (docs/deviations.md "One bank-class rule")
  // The parts, in the order one tick runs them.
  AltCurrentAutoZero autoZero_;  // the alternator current sensor's zero
  ShuntGainCorrector gain_;      // the battery shunt's gain
  SocCounter soc_;               // the count, its source, full charge, charge times
  EnergyCounter energy_;         // energies, alternator time and fuel
  BatteryAverages averages_;     // mean SoC and voltage
  OcvReanchor rest_;             // rested-voltage points of known SoC
  BatteryHealth health_;         // measured capacity and resistance
};

}  // namespace xr
