#pragma once
// Rows of the specification's buzzer table (docs/protections.md "Protections"), in order; Event::detail of an
// AlarmCondition event.
#include <cstddef>
#include <string_view>

namespace xr {

enum class AlarmRow {
  TempHigh,            // TempAlarm
  TempLow,             // TempAlarmLow (0 = off)
  VoltageHigh,         // VoltageAlarmHigh
  VoltageLow,          // VoltageAlarmLow (> 8 V floor)
  AltCurrentHigh,      // CurrentAlarmHigh
  BatteryCurrentHigh,  // MaximumAllowedBatteryAmps
  InaOvervoltage,      // INA228 hardware OV latch
  TempSensorDead,      // no valid read for > 20 s
  EfficiencyAnomaly,   // effAnomalyAlarmActive
  FaultMode,           // critical / warning / lockout mode (docs/install.md, the buzzer on GPIO21)
  TempTaskHung,        // NOT gated by AlarmActivate
  BmsStale,            // added here: BMS limits silent for BmsStaleS
  BmsMismatch,         // added here: the BMS's values do not fit the bank (its own BmsMismatch event)
  ChargingHeld,  // added here: charging held 15 min with the engine running (its own ChargingHeld event)
};
inline constexpr std::size_t kAlarmRowCount = 14;

}  // namespace xr
