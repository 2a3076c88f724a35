#pragma once
// The devices one control cycle touches, by seam. Identical on the board
// (i2c-dev drivers, sysfs PWM, libgpiod, /dev/watchdog) and in simulation
// (the same drivers on the simulated I2C bus, simulated outputs).
#include <array>

#include "core/inputs.h"
#include "core/outputs.h"
#include "drivers/hal/outputs.h"

namespace xr::rt {

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
};

// Supplies the simulator's truth for the sim_* columns (simulation only).
struct SimTruth;
class TruthSource {
 public:
  virtual ~TruthSource() = default;
  virtual void fill(SimTruth& t) noexcept = 0;
};

// Called on the control thread at the start of every tick, before anything
// else: the simulation plays its scenario events here and the slow sensor
// readers are relayed into the hand-offs. An exception thrown here leaves
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
};

}  // namespace xr::rt
