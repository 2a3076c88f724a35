#pragma once
// Regulator's private state and the values one step's stages hand each other
// (regulator_step.cpp). Only regulator*.cpp include this.
#include "battery/battery_monitor.h"
#include "control/bank_reading.h"
#include "control/charge_hold.h"
#include "control/control_law.h"
#include "control/mode_report.h"
#include "control/operator_commands.h"
#include "control/pending_events.h"
#include "control/regulator.h"
#include "health/alternator_wear.h"
#include "health/belt_slip.h"
#include "protection/battery_temperature.h"
#include "protection/mode_selection.h"
#include "protection/protection_supervisor.h"

namespace xr {

struct Regulator::State {
  explicit State(const Params& params) : p(params), law(params), prot(params), bat(params) {}

  Params p;                         // the running parameter set
  ControlLaw law;                   // the loops (docs/control.md)
  ProtectionSupervisor prot;        // detectors, mode inputs, shutdown, fast-OV (docs/protections.md)
  BatteryMonitor bat;               // auto-zero, SoC, energy (docs/batteries.md)
  BatteryTemperatureGuard batTemp;  // docs/batteries.md "Temperature rules"
  AlternatorWear wear;              // docs/operations.md "Alternator wear"
  BeltSlipDetector belt;            // docs/operations.md "Belt slip"
  ChargeHoldDetector hold;          // docs/protections.md "Charging held"
  OperatorCommands ops;             // the owner's field commands
  BankReading bank;                 // not set up: the bank class from the battery
  ModeReport report;                // the last mode / field told (one event per change)
  PendingEvents pending;            // command events for the next step's batch
  TimeNs lastHealthTick = 0;        // the wear and belt-slip dt
  TimeNs lastHoldTick = 0;          // the charging-held dt
  Params compensated;               // p with temperature-compensated targets (when compensating)
  Outputs out;                      // what the last step decided
  TimeNs now = 0;                   // the last step's time (commands between ticks stamp with it)
};

// What decideDuty() hands the field gate, the battery and the telemetry.
struct DutyDecision {
  double duty = 0.0;                           // the duty decided, before the field gate
  bool field = false;                          // the field enable decided
  bool fastOvActive = false;                   // a fast-OV supervisor clamps this tick
  GovMode govMode = GovMode::GOV_NORMAL_SLEW;  // the governor's mode this tick
};

// One step's values, computed by one stage and read by the later ones.
struct Regulator::Tick {
  explicit Tick(const Inputs& inputs) : in(inputs) {}
  const Inputs& in;
  ControlSensors cs;              // the corrected sensors (readSensors)
  const Reading* temp = nullptr;  // the alternator temperature the TempSource names
  bool autoZeroActive = false;    // the auto-zero owns the field this tick
  TickSnapshot snap;              // what mode selection saw
  ModeDecision d;                 // the mode and its reason (selectMode)
  DutyDecision act;               // the duty and field (decideDuty)
};

}  // namespace xr
