#pragma once
// CurrentCommand: the alternator current the AUTO path asks for and the caps
// on it (docs/control.md "Command path"): the RPM table, the thermal derate,
// MaxTableValue, MaximumAllowedBatteryAmps, the warm-up ceiling, the BMS's
// and the battery temperature's battery-current caps, then the tuning wave
// and the zero-current hold => uTargetRaw; the fast-OV cap => uTargetAmps.
#include "control/thermal_derate.h"
#include "core/inputs.h"
#include "params/params.h"

namespace xr {

// What the command reads each AUTO tick.
struct CommandInputs {
  TimeNs now = 0;
  double dtSec = 0.0;  // the control dt (fresh CH1)
  double rpm = kNoValue;
  double IBV = kNoValue;
  double TempToUse = kNoValue;
  TimeNs tempStamp = 0;
  double Bcur = kNoValue;
  double pidSignal = 0.0;            // the alternator current the PID sees
  double bmsBatteryCapA = 1e300;     // the BMS's CCL on the battery
  double batteryChargeCapA = 1e300;  // the battery temperature's cap
  bool tuningMode = false;           // TuningMode: the wave below every cap
  double waveTarget = 0.0;           // the tuning wave of this tick (TuningMode only)
  bool zeroHold = false;             // MaintainMode / idle hold: Icv -> 0
};

// What limits the command, for the next tick's thermal anti-windup.
struct CeilingInputs {
  bool zeroHold = false;
  double fastOvCapA = 1e300;
  bool voltageControlActive = false;
  double Icv = 0.0;
  bool fullField = false;         // the duty at MaxDuty with a primed current filter
  double measuredFiltered = 0.0;  // MeasuredAmps_filtered
};

class CurrentCommand {
 public:
  static constexpr double kNoCeiling = 1e300;

  // One AUTO tick: returns uTargetRaw.
  double update(const CommandInputs& in, const Params& p) noexcept;
  // The fast-OV supervisors' cap of this tick => uTargetAmps.
  void applyFastOvCap(double capA) noexcept;
  // Non-thermal ceiling for T0's implied-penalty anti-windup (next tick).
  void noteCeiling(const CeilingInputs& in, const Params& p) noexcept;
  // Outside AUTO no ceiling binds the thermal integrator.
  void clearCeiling() noexcept { nonThermalCeiling_ = kNoCeiling; }
  // Field enable rising edge: the warm-up ceiling starts now.
  void onFieldTurnOn(TimeNs now) noexcept { fieldOnAt_ = now; }

  double I_cap() const noexcept { return I_cap_; }
  double I_cmd() const noexcept { return I_cmd_; }
  double uTargetRaw() const noexcept { return uTargetRaw_; }
  double uTargetAmps() const noexcept { return uTargetAmps_; }
  bool warmupActive() const noexcept { return warmupActive_; }
  double bmsAltCap() const noexcept { return bmsAltCap_; }
  bool bmsCapActive() const noexcept { return bmsCapActive_; }
  const ThermalDerate& thermal() const noexcept { return thermal_; }

 private:
  ThermalDerate thermal_;           // the alternator temperature's penalty (docs/control.md "Thermal")
  double I_cap_ = 0.0;              // the RPM table's current at this speed
  double I_cmd_ = 0.0;              // I_cap after every cap, before tuning / zero hold
  double uTargetRaw_ = 0.0;         // the command before the fast-OV cap
  double uTargetAmps_ = 0.0;        // the command after the fast-OV cap
  double nonThermalCeiling_ = 0.0;  // the tightest other cap at the last tick (thermal anti-windup)
  TimeNs lastTempStamp_ = 0;        // the temperature sample seen last (fresh when it changes)
  bool warmupActive_ = false;       // the warm-up ceiling binds this tick
  TimeNs fieldOnAt_ = -1;           // the field's last turn-on (-1: never): the warm-up's start
  double bmsAltCap_ = kNoCeiling;   // the battery caps carried to the alternator (load + cap)
  bool bmsCapActive_ = false;       // that cap binds the command this tick
};

}  // namespace xr
