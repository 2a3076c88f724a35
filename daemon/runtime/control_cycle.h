#pragma once
// ControlCycle: the ONE loop body shared by the board and the simulation
// (docs/architecture.md "Threads"):
//
//   commands + Params swap (between ticks) → read INA228 + ADS1115 → merge
//   slow sensors and discrete inputs into Inputs → Regulator::step → write
//   PWM duty, GPIO4 enable, buzzer, INA mode/BOVL → feed the watchdog only
//   after a healthy cycle → publish snapshot, events, telemetry rows.
//
// Runs on the RT thread: no allocation, no locks, no logging.
#include <cstdint>

#include "drivers/hal/clock.h"
#include "runtime/control_core.h"
#include "runtime/cycle_devices.h"
#include "runtime/handoffs.h"
#include "runtime/loop_stats.h"

namespace xr::rt {

struct CycleConfig {
  TimeNs rowPeriod = fromMs(100);  // telemetry rows for the CSV (0 = none)
  bool blockOnFullRows = false;    // --speed max: wait for the CSV writer instead of dropping
  int maxCommandsPerTick = 8;
  // --speed max only (no deadlines, nobody watching in real time): store the
  // whole snapshot every Nth tick and time compute/I-O every Mth tick. Both
  // cost more than the control law itself when done every tick. Rows, events
  // and the final state are never thinned.
  int publishEveryTicks = 1;
  int timeEveryTicks = 1;
  // RpmSource = n2k (docs/integrations.md): the RPM input is the engine speed the CAN
  // service posts (Handoffs::engineRpm), not the tach on ADS1115 CH2. None
  // for fresh::kEngineRpmMaxAgeS (a silent ECU, core/freshness.h) reads 0 rpm, as a lost tach does.
  bool rpmFromN2k = false;
  // The thinning for an unpaced run (--speed max, SimRunner at speed 0):
  // ~10 snapshots per simulated second at 400 Hz.
  void thinForUnpacedRun() noexcept {
    publishEveryTicks = 40;
    timeEveryTicks = 16;
  }
};

class ControlCycle {
 public:
  // `timing` is a real (wall) clock used only to measure I/O and compute
  // time; in simulation the loop's own clock is virtual.
  ControlCycle(ControlCore& core, const CycleDevices& devices, Handoffs& handoffs, LoopStats& stats,
               const Clock& timing, CycleConfig config = {});

  // Where t_s = 0 is (set by the loop before the first tick).
  void setStart(TimeNs start) noexcept { start_ = start; }

  // One tick at time `now`. True when healthy (sensors read, step done,
  // every output written); only then is the watchdog fed. Throws only what
  // the TickHook throws.
  bool tick(TimeNs now);

  // Between ticks: service ADS1115 ALERT/RDY edges until `deadline` (loop
  // clock). Returns at once when no ready line is wired.
  void serviceEdges(TimeNs deadline) noexcept;

  // Stop path: ask the core for its controlled ramp (SYS_MODE_OFF →
  // MODE_DISABLED_RAMP); the loop keeps ticking until fieldIsOff().
  void beginShutdown() noexcept;
  bool fieldIsOff() const noexcept { return !lastEnable_ && lastDuty_ <= 0.0; }
  // Publish the latest state now (the loop calls it when it ends, so a
  // thinned publish never hides the final state).
  void publishLatest() noexcept;

  // Field enable LOW first, then duty 0, buzzer off. Safe to call any time
  // on the control thread; also publishes the final state.
  void driveSafeState() noexcept;

  const RuntimeHealth& health() const noexcept { return health_; }
  std::uint64_t ticks() const noexcept { return tick_; }

 private:
  static constexpr int kMaxEdgesPerPeriod = 16;
  static constexpr int kLedgerEveryTicks = 100;
  static constexpr int kSummaryEveryTicks = 64;  // quantiles are not free: ~6 Hz at 400 Hz
  // The periodic extras fall on the ticks that are multiples of their
  // period (timing: timeEveryTicks, the thinned snapshot store:
  // publishEveryTicks, the ledger: 100, the loop summary: 64); a period <= 1
  // means every tick.
  bool onEvery(int ticks) const noexcept;
  // Compute/I-O timing of this tick and of the edges serviced before it.
  bool timedTick() const noexcept { return onEvery(cfg_.timeEveryTicks); }
  // The per-tick helpers below run once per tick from tick() only.
  void applyPending() noexcept;
  void mergeSlowInputs() noexcept;
  void mergeTemperature() noexcept;
  void mergeVictron() noexcept;
  void mergeEngineRpm() noexcept;
  void mergeBatteryTemp() noexcept;
  void readDiscreteInputs() noexcept;
  bool writeOutputs(const Outputs& out) noexcept;
  // What this tick publishes: the snapshot store and/or a telemetry row.
  // Decided before the step, while tick_ is still this tick's number.
  struct PublishPlan {
    bool store = false;
    bool row = false;
    bool summary = false;  // refresh summary_ first
  };
  PublishPlan planPublish(TimeNs now) const noexcept;
  void publish(const Outputs& out, TimeNs now, PublishPlan plan) noexcept;
  void publishRow(TimeNs now) noexcept;
  void storeSnapshot(const Outputs& out, TimeNs now) noexcept;

  ControlCore& core_;
  CycleDevices dev_;
  Handoffs& h_;
  LoopStats& stats_;
  const Clock& timing_;
  CycleConfig cfg_;

  Inputs in_{};
  RuntimeHealth health_{};
  LoopStatsSummary summary_{};
  SimTruth truth_{};
  RuntimeSnapshot scratch_{};  // built in place: the snapshot is large
  TimeNs start_ = 0;
  TimeNs lastRow_ = 0;
  bool rowsStarted_ = false;
  std::uint64_t tick_ = 0;
  const Outputs* lastOut_ = nullptr;
  TimeNs lastNow_ = 0;
  TimeNs lastTempStamp_ = 0, lastVictronStamp_ = 0, lastEngineRpmStamp_ = 0;
  TimeNs lastBatteryTempStamp_ = 0;
  TimeNs lastAdsStamp_[4] = {0, 0, 0, 0};
  TimeNs lastInaStamp_ = 0;
  std::array<std::uint32_t, 4> freshTotals_{};  // sensors that do not count: fresh flags summed

  // What the outputs are known to be (written successfully).
  bool outputsKnown_ = false;
  bool lastEnable_ = false;
  double lastDuty_ = 0.0;
  bool lastBuzzer_ = false;
  bool stopping_ = false;
};

}  // namespace xr::rt
