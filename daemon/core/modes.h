#pragma once
// The specification's enumerations, spelled as the specification spells them so telemetry,
// journal lines and spec grep together.
#include <optional>
#include <string_view>

namespace xr {

// docs/protections.md "Mode priority" + docs/control.md "Limp Home".
enum class FieldControlMode {
  MODE_CRITICAL_RAMP,
  MODE_WARNING_RAMP_AND_LOCKOUT,
  MODE_LOCKOUT_RAMP,
  MODE_DISABLED_RAMP,
  MODE_NORMAL_MANUAL,
  MODE_NORMAL_AUTO_PID,
  MODE_LIMP_HOME,
};

// docs/control.md "Charging stages".
enum class ChargeStage { BULK, ABSORPTION, FLOAT, IDLE };

// docs/control.md "Mode entry functions".
enum class SysMode { SYS_MODE_OFF, SYS_MODE_MANUAL, SYS_MODE_AUTO, SYS_MODE_FAULT };

// docs/control.md "Governor".
enum class GovMode { GOV_NORMAL_SLEW, GOV_BYPASS_SLEW, GOV_HOLD };

// Shutdown phases (docs/protections.md "Shutdown paths").
enum class ShutdownPhase { PHASE_NONE, PHASE_1, PHASE_2, PHASE_3, PHASE_4, PHASE_DONE };

// selectFieldEventReason(): what is acting. NONE when nothing is.
enum class Reason {
  NONE,
  REASON_INA_OVERVOLTAGE,
  REASON_HARD_OVERCURRENT,
  REASON_TEMP_CRITICAL,
  REASON_RPM_LOW,
  REASON_ALT_HARD_SHUTDOWN,
  REASON_VOLTAGE_DISAGREE_WARNING,
  REASON_VOLTAGE_DISAGREE_CRITICAL,
  REASON_VOLTAGE_IMPLAUSIBLE,
  REASON_TEMP_WARNING,
  REASON_TEMP_SUSTAINED,
  REASON_TEMP_STALE,
  REASON_CURRENT_STALE,
  REASON_LOCKOUT,
  REASON_AUTO_ZERO,
  REASON_IGNITION_OFF,
  REASON_ONOFF_DISABLED,
  REASON_BMS_DISABLED,
  REASON_WEATHER_MODE,
  REASON_IDLE_STAGE,
  REASON_SYS_OFF,
  REASON_LIMP_HOME,
  REASON_SYSTEM_ID,
  REASON_BMS_STALE,      // ours: the BMS went silent; charge held under BmsFallbackCapA
  REASON_BATTERY_COLD,   // battery below ChargeMinTempC: no charging (docs/batteries.md)
  REASON_BATTERY_HOT,    // battery above ChargeMaxTempC: no charging until 3 degC below
  REASON_TEMP_SOAK,      // ours: engine restarted above TemperatureLimitF; field held off until it cools
  REASON_BANK_MISMATCH,  // ours: both voltage sensors read another bank size than BulkVoltage's
};

std::string_view toString(FieldControlMode m);
std::string_view toString(ChargeStage s);
std::string_view toString(SysMode m);
std::string_view toString(GovMode m);
std::string_view toString(ShutdownPhase p);
std::string_view toString(Reason r);

std::optional<FieldControlMode> parseFieldControlMode(std::string_view s);
std::optional<ChargeStage> parseChargeStage(std::string_view s);
std::optional<Reason> parseReason(std::string_view s);

}  // namespace xr
