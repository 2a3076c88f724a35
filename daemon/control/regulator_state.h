#pragma once
// Regulator's private state and the values one step's stages hand each other
// (regulator_step.cpp). Only regulator*.cpp include this.
#include <array>
#include <cstddef>

#include "battery/battery_monitor.h"
#include "control/charge_hold.h"
#include "control/control_law.h"
#include "control/regulator.h"
#include "health/alternator_wear.h"
#include "health/belt_slip.h"
#include "protection/battery_temperature.h"
#include "protection/mode_selection.h"
#include "protection/protection_supervisor.h"

namespace xr {

struct Regulator::State {
  explicit State(const Params& params) : p(params), law(params), prot(params), bat(params) {}

  Params p;
  ControlLaw law;
  ProtectionSupervisor prot;
  BatteryMonitor bat;
  BatteryTemperatureGuard batTemp;  // docs/batteries.md "Temperature rules"
  AlternatorWear wear;              // docs/operations.md "Alternator wear"
  BeltSlipDetector belt;            // docs/operations.md "Belt slip"
  ChargeHoldDetector hold;          // docs/protections.md "Charging held"
  TimeNs lastHealthTick = 0;
  TimeNs lastHoldTick = 0;
  Params compensated;  // p with temperature-compensated targets (when compensating)
  Outputs out;

  // Operator state (commands).
  bool limpHome = false;
  bool opManual = false;
  double opManualDuty = 0.0;
  bool opOff = false;
  bool currentWeatherMode = false;

  bool firstTick = true;
  // Not set up: the bank class read from the battery (bank_reading.cpp).
  bool bankWaiting = false;
  TimeNs bankWaitSince = 0;
  Telemetry::SetupBank bank;
  FieldControlMode lastMode = FieldControlMode::MODE_DISABLED_RAMP;
  Reason lastReason = Reason::NONE;
  bool lastField = false;
  TimeNs now = 0;
  GovMode tickGovMode = GovMode::GOV_NORMAL_SLEW;  // the last step's govMode (telemetry)

  // Command results waiting for the next step's event batch.
  std::array<Event, 8> pending{};
  std::size_t pendingCount = 0;
  void queue(const Event& e) {
    if (pendingCount < pending.size()) pending[pendingCount++] = e;
  }
};

// One step's values, computed by one stage and read by the later ones.
struct Regulator::Tick {
  explicit Tick(const Inputs& inputs) : in(inputs) {}
  const Inputs& in;
  ControlSensors cs;               // the control law's view of the sensors
  const Reading* temp = nullptr;   // the alternator temperature the TempSource names
  double MeasuredAmps = kNoValue;  // alternator current, auto-zero corrected
  double Bcur = kNoValue;          // battery current, corrected
  bool autoZeroActive = false;     // the auto-zero owns the field this tick
  bool manualMode = false;         // ManualMode or the operator's manual command
  TickSnapshot snap;               // what mode selection saw
  ModeDecision d;                  // the mode and its reason
  double duty = 0.0;               // the duty decided, before the field gate
  bool field = false;              // the field enable decided
  bool fastOvActive = false;       // a fast-OV supervisor clamps this tick
  GovMode govMode = GovMode::GOV_NORMAL_SLEW;
};

}  // namespace xr
