#pragma once
// The caps on this tick's current command, each with its amps and its cause
// as numbers and enums (docs/dashboard.md "Owner model"). The control law
// applies them (docs/control.md "Command path"); the owner model turns them
// into words off the control thread, so nothing here is text. NaN = that cap
// does not apply this tick (or was not computed: the alternator-side caps
// are computed only while AUTO regulates).
#include "control/bms_limiter.h"
#include "core/inputs.h"
#include "protection/battery_temperature.h"

namespace xr {

struct CommandCaps {
  double ratingA = kNoValue;          // MaxTableValue: the alternator's rating
  double rpmTableA = kNoValue;        // the RPM cap table at this speed (getCapCurrentForRPM)
  double rpmTableTopA = kNoValue;     // the table's highest entry: the belt limit the set-up writes
  double batteryMaxA = kNoValue;      // MaximumAllowedBatteryAmps on the command
  double thermalA = kNoValue;         // the RPM cap less the thermal derate (while a penalty acts)
  double thermalPenaltyA = kNoValue;  // that penalty
  double warmupA = kNoValue;          // WarmupCeilingAmps while the warm-up ceiling acts
  double bmsA = kNoValue;             // the BMS's battery-current cap (CCL, warning ramp, stale fallback)
  BmsSource bmsSource = BmsSource::None;
  double batteryTempA = kNoValue;  // the battery-temperature rules' battery-current cap
  BatteryTempCap batteryTempCause = BatteryTempCap::NONE;
  double batteryCapAltA = kNoValue;  // the alternator current those battery caps allow (load + cap)
  double fastOvA = kNoValue;         // the fast over-voltage supervisors' cap while clamping
  bool zeroBatteryHold = false;      // MaintainMode / IdleZeroCurrent: battery current held at 0
  double commandA = kNoValue;        // I_cmd after every cap
};

// Visits every field as f("name", value), like visitControlTelemetry.
template <typename T, typename F>
void visitCommandCaps(T& t, F&& f) {
  f("ratingA", t.ratingA);
  f("rpmTableA", t.rpmTableA);
  f("rpmTableTopA", t.rpmTableTopA);
  f("batteryMaxA", t.batteryMaxA);
  f("thermalA", t.thermalA);
  f("thermalPenaltyA", t.thermalPenaltyA);
  f("warmupA", t.warmupA);
  f("bmsA", t.bmsA);
  f("bmsSource", t.bmsSource);
  f("batteryTempA", t.batteryTempA);
  f("batteryTempCause", t.batteryTempCause);
  f("batteryCapAltA", t.batteryCapAltA);
  f("fastOvA", t.fastOvA);
  f("zeroBatteryHold", t.zeroBatteryHold);
  f("commandA", t.commandA);
}

}  // namespace xr
