#pragma once
// Regulator: the pure core. One call per control tick:
//
//   Inputs (sensor samples + freshness + now) -> step() -> Outputs
//
// Owns every loop, protection and battery state as plain members. No device,
// clock, file, socket, global or heap allocation after construction.
// setParams() and command() are called between ticks only (by the same
// thread that calls step(), which drains the command queue first).
#include <memory>

#include "battery/ledger.h"
#include "control/outputs.h"
#include "core/charge_checks.h"
#include "core/commands.h"
#include "core/inputs.h"
#include "params/params.h"

namespace xr {

struct DutyDecision;
struct ModeDecision;

class Regulator {
 public:
  explicit Regulator(const Params& params);
  ~Regulator();
  Regulator(const Regulator&) = delete;
  Regulator& operator=(const Regulator&) = delete;

  // Replace the whole parameter set (between ticks).
  void setParams(const Params& params) noexcept;  // the real-time thread, between ticks
  const Params& params() const;

  // Apply an operator command (between ticks). Returns false, and emits a
  // CommandRejected event on the next step, when the command is not legal now.
  bool command(const Command& cmd) noexcept;  // the real-time thread, between ticks

  // One control tick.
  // Real-time thread, every tick: neither allocates nor blocks (docs/architecture.md "Threads").
  const Outputs& step(const Inputs& in) noexcept;
  const Outputs& outputs() const;

  // Persistent battery state, for the store.
  BatteryLedger ledger() const;
  void restoreLedger(const BatteryLedger& ledger);

 private:
  // One step's stages, in order (regulator_step.cpp), on the real-time thread
  // like step(). Each returns what it decided; the Tick holds those for the
  // later stages (docs/architecture.md "Control law and the step").
  struct Tick;
  void beginTick(const Tick& t) noexcept;
  bool settleBankClass(const Tick& t) noexcept;    // regulator.cpp
  bool applyToParts(const Command& cmd) noexcept;  // regulator.cpp, between ticks
  void readSensors(Tick& t) noexcept;
  void runProtections(Tick& t) noexcept;
  ModeDecision selectMode(Tick& t) noexcept;
  void enterMode(const Tick& t) noexcept;
  DutyDecision decideDuty(const Tick& t) noexcept;
  DutyDecision runAuto(const Tick& t) noexcept;
  void applyField(const Tick& t) noexcept;
  void updateBattery(const Tick& t) noexcept;
  void updateChargeChecks(const Tick& t) noexcept;  // regulator_hold.cpp
  ChargeHold chargeHoldCause(const Tick& t) const noexcept;
  void updateHealth(const Tick& t) noexcept;
  void fillInputTelemetry(const Tick& t) noexcept;
  void fillStateTelemetry(const Tick& t) noexcept;
  void fillCapsTelemetry(const Tick& t) noexcept;

  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace xr
