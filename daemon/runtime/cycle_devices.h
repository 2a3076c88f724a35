#pragma once
// The devices one control cycle touches, by seam. Identical on the board
// (i2c-dev drivers, sysfs PWM, libgpiod, /dev/watchdog) and in simulation
// (the same drivers on the simulated I2C bus, simulated outputs).
#include <array>
#include <cstdint>

#include "control/outputs.h"
#include "core/inputs.h"
#include "drivers/hal/outputs.h"

namespace xr::rt {

// Cumulative ADS1115 results per channel since start (several may arrive in
// one tick with ready-edge pacing, so the per-tick fresh flags undercount).
struct SampleCounts {
  std::array<std::uint32_t, 4> ads{};
  bool readyEdgeFallback = false;  // ALERT/RDY configured but silent: single-shot pacing
};

// The fast sensors read on the RT thread: INA228 + ADS1115 through their
// drivers. Implementations fill only their own fields of Inputs (values,
// stamps, freshness, inaPresent, ...) and never throw.
class FastSensors {
 public:
  virtual ~FastSensors() = default;
  // Read whatever is due at `now`. Returns false when an I/O error occurred
  // this tick (the affected readings simply stay stale for the core).
  virtual bool read(TimeNs now, Inputs& in) noexcept = 0;
  // The regulator's requests to the INA228: conversion mode, BOVL.
  virtual void apply(const Outputs& out) noexcept = 0;
  // One ADS1115 ALERT/RDY edge (ready-edge pacing), `edge` = its timestamp
  // on the loop clock. Called between ticks on the control thread.
  virtual void onReadyEdge(TimeNs edge) noexcept { (void)edge; }
  // The counts as of the last read(), or nullptr when the sensors do not
  // count (the cycle then sums the fresh flags). Not virtual: the cycle
  // reads it after every read(), and an implementation that counts keeps
  // counts_ pointing at its own SampleCounts, current after each read().
  const SampleCounts* sampleCounts() const noexcept { return counts_; }

 protected:
  const SampleCounts* counts_ = nullptr;
};

// ADS1115 ALERT/RDY edges: libgpiod line events on the board, the chip
// model's conversion-ready pulses in simulation.
class ReadyEdgeSource {
 public:
  virtual ~ReadyEdgeSource() = default;
  // Wait for the next edge, but not past `deadline` (loop clock). 1 and its
  // stamp when an edge came, 0 when the deadline came first, -1 on error.
  virtual int waitEdge(TimeNs deadline, TimeNs* stamp) noexcept = 0;
};

// Supplies the simulator's truth for the sim_* columns (simulation only).
struct SimTruth;
class TruthSource {
 public:
  virtual ~TruthSource() = default;
  virtual void fill(SimTruth& t) noexcept = 0;
};

// Called on the control thread at the start of every tick: the simulation plays its scenario
// events and simulated 1-Wire readings here (the board's slow sensor readers post into their
// hand-offs from their own threads; nothing is relayed here). An exception thrown here leaves
// the loop through the control thread's exception path (safe state, exit 70).
class TickHook {
 public:
  virtual ~TickHook() = default;
  virtual void beforeTick(TimeNs now) = 0;
};

struct CycleDevices {
  FastSensors* sensors = nullptr;        // required
  PwmOutput* pwm = nullptr;              // required
  DigitalOutput* fieldEnable = nullptr;  // required (GPIO4)
  DigitalOutput* buzzer = nullptr;       // optional (GPIO21)
  DigitalInput* bms = nullptr;           // optional, 1 = BMS asserts "charge disabled"; not wired = enabled
  DigitalInput* ignition = nullptr;      // optional: not wired = on
  Watchdog* watchdog = nullptr;          // optional: fed after healthy cycles only
  TruthSource* truth = nullptr;          // simulation only
  TickHook* hook = nullptr;              // optional
  ReadyEdgeSource* adsReady = nullptr;   // optional: ADS1115 ALERT/RDY wired
};

}  // namespace xr::rt
