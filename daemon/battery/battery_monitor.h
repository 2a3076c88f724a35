#pragma once
// BatteryMonitor: SoC, energy accounting, full-charge detection, auto shunt
// gain, alternator-current auto-zero and charge-time prediction
// (docs/batteries.md). Pure core: no I/O, no clock, no allocation
// after construction; time comes from Inputs::now.
//
// How Regulator::step must call it, every tick, in this order:
//
//   1. mon.checkAutoZeroTriggers(in, events);   // BEFORE the control step
//      const bool autoZeroActive = mon.processAutoZero(in, events);
//      If autoZeroActive: mode = MODE_LOCKOUT_RAMP, fieldEnable = LOW,
//      duty = MinDuty for this tick; the normal control path must not run
//      ("Critical ordering note" of the seed).
//   2. const double MeasuredAmps = mon.correctedAltAmps(in.altCurrentRaw.value);
//      const double Bcur = mon.correctedBcur(in.Bcur.value);
//      Use these everywhere the seeds use MeasuredAmps / Bcur (the control
//      loop's MaintainMode path uses Bcur, never getBatteryCurrent()).
//   3. (control + protections step)
//   4. mon.updateBatterySoc(in, MeasuredAmps, events);   // every tick; it
//      integrates every tick and runs the seed's body each SOCUpdateInterval,
//      and calculateChargeTimes() each INA_SLOW_INTERVAL_MS.
//   5. mon.fillTelemetry(outputs.telemetry.battery);
//      outputs.telemetry.soc_pct = mon.socPercent(); charged_wh_lifetime etc.
//
// Between ticks (command()): resetSocGain(), resetAltZero(), setSoc(pct).
// setParams() whenever Params are replaced. ledger()/restoreLedger() for the
// store (restoreLedger before the first step, or between ticks).
#include <cstdint>

#include "battery/battery_telemetry.h"
#include "battery/capacity_tracker.h"
#include "battery/ledger.h"
#include "battery/resistance_estimator.h"
#include "core/events.h"
#include "core/inputs.h"
#include "core/time.h"
#include "params/params.h"

namespace xr {

// Constants the seed uses but leaves unnamed or unvalued. Chosen here; each
// one is a safety / plausibility decision, so it is not user-settable.
namespace battery_k {
// Field held off this long for an auto-zero (the first 2 s are the settle
// window and are not sampled). 10 s gives ~8 s of samples: at the ADS1115's
// CH1 rate that is hundreds of samples, enough to average Hall noise away,
// while a 10 s charging gap once an hour costs < 0.3 % of charge.
inline constexpr std::int64_t AUTO_ZERO_DURATION_MS = 10000;
// Largest Hall zero offset accepted from an auto-zero. A bigger value means
// current was really flowing (field not off, wiring fault): keep the old zero.
inline constexpr double AUTO_ZERO_MAX_OFFSET_A = 10.0;
// Auto shunt-gain correction (applySocGainCorrection guard clauses):
// at most one correction per 24 h: full-charge detection repeats every
// SOCUpdateInterval while it holds, and a calibration should average over a
// whole cycle, not react to the same full charge twice.
inline constexpr std::int64_t MIN_GAIN_CORRECTION_INTERVAL_MS = 24LL * 3600 * 1000;
// |expected - calculated| / expected above this is a sensor or wiring fault,
// not a calibration error: do nothing.
inline constexpr double MAX_REASONABLE_ERROR = 0.20;
// Per-event rate limit: the factor moves at most 2 % per full charge.
inline constexpr double MAX_GAIN_ADJUSTMENT_PER_CYCLE = 0.02;
// Absolute bounds: a shunt is never off by more than 10 % after manufacture.
inline constexpr double MIN_DYNAMIC_GAIN_FACTOR = 0.90;
inline constexpr double MAX_DYNAMIC_GAIN_FACTOR = 1.10;
// Plausibility floor of both capacities (Ah), as the seed.
inline constexpr double MIN_PLAUSIBLE_CAPACITY_AH = 10.0;
// The seed commits the coulomb accumulator in 0.01 Ah steps, remainder kept.
inline constexpr double COULOMB_COMMIT_AH = 0.01;
// INA228 current older than this is treated as absent (no integration).
inline constexpr std::int64_t INA_STALE_FOR_SOC_MS = 2000;
// Solar PPV older than this is not integrated.
inline constexpr std::int64_t SOLAR_STALE_MS = 10000;
}  // namespace battery_k

// SoC assumed before anything was restored or measured (see the constructor).
inline constexpr double kUnknownSocPercent = 100.0;

// Why an auto-gain correction was skipped (detail code of events/tests).
enum class GainGuard {
  Applied = 0,
  FeatureOff,
  TooSoon,      // MIN_GAIN_CORRECTION_INTERVAL
  NoReference,  // no full charge / setSoc since boot: count is not a measurement
  ImplausibleCapacity,
  ErrorTooLarge,  // MAX_REASONABLE_ERROR
};

class BatteryMonitor {
 public:
  explicit BatteryMonitor(const Params& p);
  void setParams(const Params& p) noexcept;

  // ---- auto-zero (before the control step) --------------------------------
  // Starts an auto-zero when AutoAltCurrentZero, not running, RPM >= 200 and
  // (hourly interval elapsed or temperature moved >= 20 degF). The hourly
  // timer starts at the first tick; the temperature baseline is the first
  // valid temperature. Emits AutoZeroStarted.
  void checkAutoZeroTriggers(const Inputs& in, EventBatch& ev) noexcept;
  // Runs the field-off sampling window. Returns true while active (the caller
  // forces MODE_LOCKOUT_RAMP, field LOW, duty MinDuty). On completion sets
  // DynamicAltCurrentZero = mean raw CH1 after the 2 s settle and emits
  // AutoZeroDone (a = new zero A, detail 0 = ok, 1 = no samples, 2 = rejected
  // as implausible).
  bool processAutoZero(const Inputs& in,
                       EventBatch& ev) noexcept {  // inline idle path: no call on almost every tick
    return autoZeroActive_ && processActiveAutoZero(in, ev);
  }
  bool autoZeroActive() const noexcept { return autoZeroActive_; }

  // ---- corrected sensor values ---------------------------------------------
  double correctedAltAmps(double rawAmps) const noexcept { return rawAmps - ledger_.DynamicAltCurrentZero; }
  double correctedBcur(double raw) const noexcept { return raw * ledger_.DynamicShuntGainFactor; }
  // IBV (INA228 bus voltage) always.
  double getBatteryVoltage(const Inputs& in) const noexcept;
  // INA228 Bcur x gain, or VictronCurrent when BatteryCurrentSource == 3 and
  // its sample is no older than VICTRON_STALE_MS (else falls back to INA228).
  double getBatteryCurrent(const Inputs& in) const noexcept;
  bool usingVictronCurrent(const Inputs& in) const noexcept;

  // ---- SoC and energy (after the control step, every tick) -----------------
  // measuredAltAmps = correctedAltAmps(raw CH1). Integrates current and power
  // every tick (zero-order hold of the latest sample), runs the seed's
  // updateBatterySoc body every SOCUpdateInterval on the interval totals and
  // calculateChargeTimes() every INA_SLOW_INTERVAL_MS.
  void updateBatterySoc(const Inputs& in, double measuredAltAmps, EventBatch& ev) noexcept;

  // ---- commands (between ticks) --------------------------------------------
  void resetSocGain() noexcept;      // handleSocGainReset: DynamicShuntGainFactor = 1.0
  void resetAltZero() noexcept;      // handleAltZeroReset: DynamicAltCurrentZero = 0
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
  // only when the SoC body, the charge-time prediction, an auto-zero, a
  // command, setParams or restoreLedger runs, so the whole struct is
  // refilled only then; otherwise only the per-tick fields are written.
  // The result is always equal to fillTelemetry() (battery_test checks it).
  void updateTelemetry(BatteryTelemetry& t) noexcept;
  double socPercent() const noexcept {  // inline: read several times per tick
    const double cap = p_.BatteryCapacity_Ah;
    if (!(cap > 0.0)) return 0.0;
    return ledger_.CoulombCount_Ah / cap * 100.0;
  }
  // False while the SoC is the constructor's guess: no valid ledger restored,
  // no setSoc, no full-charge detection yet. Control may ignore SOC gating
  // (StageInputs::socValid) while this is false.
  bool socKnown() const noexcept { return socSource() == SocSource::Counted; }
  SocSource socSource() const noexcept { return static_cast<SocSource>(static_cast<int>(ledger_.SocSource)); }
  bool fullChargeDetected() const noexcept { return FullChargeDetected_; }
  // The charging stage ended absorption on its tail current: the bank is
  // full, a detected full charge like the monitor's own (its voltage and
  // tail thresholds may differ from the stage's, and a bank that rests
  // after absorption never meets them again; docs/batteries.md).
  void chargeCompletedOnTail(TimeNs now, EventBatch& ev) noexcept;
  double chargedEnergyLifetimeWh() const noexcept;
  double alternatorChargedEnergyLifetimeWh() const noexcept;
  // The bank's measured capacity (NaN until measured) and resistance at 25 degC
  // (NaN until enough steps were seen): battery_health.cpp.
  double capacityMeasuredAh() const noexcept { return capacity_.measuredAh(); }
  int capacityCycles() const noexcept { return capacity_.cycles(); }
  double batteryResistanceMohm() const noexcept { return resistance_.medianMohm(); }
  // Last applySocGainCorrection outcome (tests, diagnostics).
  GainGuard lastGainGuard() const noexcept { return lastGainGuard_; }

  // Peukert factor of the seed, (PeukertRatedCurrent_A / I)^(n-1) clamped to
  // 0.5..2.0, or 1 at or below C/100. Public for tests.
  static double peukertFactor(double dischargeCurrent_A, double capacity_Ah, double ratedCurrent_A,
                              double exponent) noexcept;

 private:
  bool processActiveAutoZero(const Inputs& in,
                             EventBatch& ev) noexcept;  // processAutoZero while autoZeroActive_
  struct Energy {  // one accumulator: session + lifetime (whole Wh + fraction)
    double session_Wh = 0.0;
    double lifetimeFraction_Wh = 0.0;
  };
  void runSocBody(TimeNs now, double elapsed_s, EventBatch& ev) noexcept;
  void countCoulombs(double elapsed_s) noexcept;
  void countFuel() noexcept;
  void applySocGainCorrection(TimeNs now, EventBatch& ev) noexcept;
  void declareFullCharge(TimeNs now, EventBatch& ev) noexcept;
  void setSocSource(SocSource s) noexcept {
    ledger_.SocSource = static_cast<double>(s);
    telemetryStale_ = true;
  }
  void estimateSocAtRest(double dt_s, double amps, double volts, double altAmps) noexcept;
  // battery_ocv.cpp: a lead-acid bank at rest (little current, alternator
  // off), and the SoC its rested voltage says.
  bool leadAcidAtRest(double amps, double volts, double altAmps) const noexcept;
  double socFromRestVolts(double volts) const noexcept;
  void calculateChargeTimes(const Inputs& in) noexcept;
  // battery_health.cpp: the measured capacity's points, the resistance.
  void trackHealth(const Inputs& in, double dt_s, double amps, double volts, double altAmps) noexcept;
  void restedVoltagePoint(double dt_s, double amps, double volts, double tempC, bool resting) noexcept;
  void capacityPoint(TimeNs now, double socPct, bool full, EventBatch& ev) noexcept;
  void commitEnergy(Energy& e, double& lifetimeWhole, double delta_Wh) noexcept;
  double temperatureF(const Inputs& in) const noexcept;

  Params p_;
  BatteryLedger ledger_;
  // Something behind a slow telemetry field changed since the last
  // updateTelemetry() (see there).
  bool telemetryStale_ = true;

  // Per-interval integrals (zero-order hold, reset each SOC body run).
  bool started_ = false;
  TimeNs lastTick_ = 0;
  TimeNs lastSocUpdate_ = 0;
  TimeNs lastChargeTimes_ = 0;
  double intAh_ = 0.0;           // signed battery Ah (raw, before efficiency/Peukert)
  double intChargeWh_ = 0.0;     // V*I > 0
  double intDischargeWh_ = 0.0;  // |V*I| for V*I < 0
  double intAltWh_ = 0.0;        // V * MeasuredAmps while alternatorIsOn
  double intSolarWh_ = 0.0;      // PPV
  double intAltOn_s_ = 0.0;
  double intSoc_s_ = 0.0;    // seconds integrated this interval
  double intV_s_ = 0.0;      // V*s
  double intVtime_s_ = 0.0;  // seconds with a valid voltage

  // Latest samples used by the body.
  double currentBatteryVoltage_ = 0.0;
  double batteryCurrentForSoC_ = 0.0;
  bool usingVictron_ = false;
  bool socInputsValid_ = false;
  // The start-up estimate from the rested voltage (battery_ocv.cpp).
  double restTimer_s_ = 0.0;
  double restVoltSum_ = 0.0;
  double lastValidVoltage_ = 0.0;

  // Session energies and figures.
  Energy charged_, discharged_, altCharged_, solar_;
  double AlternatorOnTime_s_ = 0.0;
  double AlternatorFuelUsed_L_ = 0.0;
  double fuelFraction_L_ = 0.0;  // hundredths-of-a-litre commit (seed)
  double socAccumulator_ = 0.0, totalSocSampleTime_ = 0.0;
  int nominalVoltage_ = 12;

  // Full charge / gain.
  double FullChargeTimer_s_ = 0.0;
  bool FullChargeDetected_ = false;
  bool gainReferenceValid_ = false;  // a full charge or setSoc happened this session
  double unclampedCount_Ah_ = 0.0;   // count since the reference, without the 0..cap clamp
  bool haveGainCorrection_ = false;
  TimeNs lastGainCorrectionTime_ = 0;
  GainGuard lastGainGuard_ = GainGuard::FeatureOff;

  // Auto-zero.
  bool autoZeroActive_ = false;
  TimeNs autoZeroStartTime_ = 0;
  TimeNs lastAutoZeroTime_ = 0;
  bool haveAutoZeroTemp_ = false;
  double lastAutoZeroTemp_ = 0.0;
  double autoZeroAccumulator_ = 0.0;
  long autoZeroSampleCount_ = 0;

  // Health (battery_health.cpp).
  CapacityTracker capacity_;
  ResistanceEstimator resistance_;
  double bmsSocPct_ = kNoValue;  // a fresh SoC from a BMS, this interval
  double healthRest_s_ = 0.0;    // lead-acid rest towards a rested-voltage point
  double healthRestV_s_ = 0.0, healthRestA_s_ = 0.0, healthRestAvg_s_ = 0.0;
  bool healthRestTaken_ = false;         // this rest gave its point
  double pendingRestSocPct_ = kNoValue;  // a rested-voltage point for the next SoC body

  // Predictions.
  double timeToFullChargeMin_ = -999.0;
  double timeToFullDischargeMin_ = -999.0;
};

}  // namespace xr
