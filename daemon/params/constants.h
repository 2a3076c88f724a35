#pragma once
// The specification's hard-coded constants, each named as in the specification that defines it.
// Not user-settable by design: changing one changes the safety case.
#include <cstdint>

namespace xr::k {

// docs/protections.md "Protections": arming dead-band.
inline constexpr double PRED_GUARD = 0.06;  // V
// "Group 1": dv/dt accepted only when INA samples are 1–100 ms apart.
inline constexpr double DVDT_MIN_SAMPLE_S = 0.001;
inline constexpr double DVDT_MAX_SAMPLE_S = 0.100;
// "Group 3 — iExcess": release hysteresis and cap slope.
inline constexpr double IEXCESS_HYST = 2.0;  // A
inline constexpr double K_IE = 1.0;          // A/A
// "Alternator Hard Shutdown": slew-bypass accelerator offset.
inline constexpr double HARD_SHUTDOWN_BYPASS_OFFSET_V = 0.5;
// "INA228 Hardware ALERT": VoltageHardwareLimit = BulkVoltage + this.
inline constexpr double INA_OV_OFFSET_V = 0.3;
// First-boot default of AlternatorHardShutdownV = BulkVoltage + this.
inline constexpr double HARD_SHUTDOWN_DEFAULT_OFFSET_V = 0.3;
inline constexpr std::int64_t INA_OV_DISAGREE_SUPPRESS_MS = 10000;
// INA228 software latch cadences: release check, definitive recheck, new-event poll.
inline constexpr std::int64_t INA_LATCH_RELEASE_CHECK_MS = 3000;
inline constexpr std::int64_t INA_LATCH_RECHECK_MS = 10000;
inline constexpr std::int64_t INA_LATCH_POLL_MS = 5000;
// "Disagreement Critical".
inline constexpr std::int64_t VoltageDisagreeCriticalTimeoutMs = 3000;
inline constexpr double DISAGREE_CRITICAL_12V = 1.0;
inline constexpr double DISAGREE_CRITICAL_24V = 2.0;
inline constexpr double DISAGREE_CRITICAL_48V = 4.0;
inline constexpr double SENSOR_DEAD_V = 0.1;  // either sensor below this = critical at once
// "Implausibility": buffer around the system class range.
inline constexpr double PLAUSIBLE_BUFFER_V = 0.5;
// "T4 — TempTask Hang" and "T5 — Temperature Data Stale".
inline constexpr std::int64_t TEMP_TASK_TIMEOUT = 20000;  // ms
inline constexpr std::int64_t TEMP_STALE_MS = 20000;
inline constexpr std::int64_t TEMP_BOOT_GRACE_MS = 60000;
inline constexpr double TEMP_VALID_MIN_F = -50.0;
inline constexpr double TEMP_VALID_MAX_F = 400.0;
// "Hard Overcurrent": HardOCTripAmps = MaxTableValue + this.
inline constexpr double HARD_OC_OFFSET_A = 10.0;
// docs/control.md "Charging stages": two-sided band below BulkVoltage.
inline constexpr double BULK_V_BAND_ENTER = 0.05;
inline constexpr double BULK_V_BAND_EXIT = 0.10;
// "FLOAT": unconditional re-bulk after 12 h in float.
inline constexpr std::int64_t FLOAT_DURATION_S = 43200;
// "Voltage CV Loop": asymmetric integration, tracker gain, minimum e_needed.
inline constexpr double KI_DOWN_MULTIPLIER = 7.0;
inline constexpr double CV_TRACKER_KT = 2.0;  // 1/s
inline constexpr double CV_E_NEEDED_MIN_V = 0.02;
inline constexpr double CV_OVERSHOOT_RELEASE_V = 0.02;  // GOV bypass latch release
// "Absorption": tail exit suppressed while thermally constrained.
inline constexpr double TAIL_THERMAL_PENALTY_A = 2.0;
// Added here (docs/deviations.md "Tail current"): the tail counts only while IBV is
// within this of the absorption target (the voltage loop holds it).
inline constexpr double TAIL_HOLD_BAND_V = 0.05;
// Added here ("Full bank"): after a field rest ends, the RPM gate keeps trusting the
// pre-rest RPM this long while the tach signal comes back (LM2907 ~2 s).
inline constexpr std::int64_t RPM_REST_GRACE_MS = 3000;
// "Temperature PID": slope ring buffer.
inline constexpr int THERMAL_SLOPE_BUF = 13;
// "CVTuningMode".
inline constexpr double CV_HIGH_DEADBAND_V = 0.025;
inline constexpr double CV_LOW_GRACE_SEC = 1.0;
inline constexpr double CV_LOW_RAMP_SEC = 10.0;
inline constexpr double CV_SETTLE_V_THRESH = 0.05;
inline constexpr int TUNING_LOG_SIZE = 50;
// Added here: CVTuningMode's HIGH target stays this far under AlternatorHardShutdownV.
inline constexpr double CV_TUNING_TRIP_MARGIN_V = 0.2;
// "TuningMode": base of the square wave.
inline constexpr double TUNING_BASE_A = 5.0;
inline constexpr double TUNING_SCORE_SLEW_A_PER_S = 1.0;
// "Limp Home".
inline constexpr double LIMP_HOME_DUTY = 30.0;  // %
inline constexpr std::int64_t LIMP_HOME_LOG_MS = 30000;
// "Alarm Buzzer".
inline constexpr std::int64_t ALARM_CHECK_MS = 250;
inline constexpr std::int64_t ALARM_MESSAGE_THROTTLE_MS = 30000;
inline constexpr double VOLTAGE_ALARM_LOW_FLOOR_V = 8.0;
// docs/batteries.md.
inline constexpr std::int64_t AUTO_ZERO_INTERVAL = 3600000;  // ms
inline constexpr double AUTO_ZERO_TEMP_DELTA = 20.0;         // degF
inline constexpr double AUTO_ZERO_MIN_RPM = 200.0;
inline constexpr std::int64_t AUTO_ZERO_SETTLE_MS = 2000;
inline constexpr std::int64_t VICTRON_STALE_MS = 10000;
inline constexpr std::int64_t INA_SLOW_INTERVAL_MS = 1100;
inline constexpr double PREDICTION_NA = -999.0;  // "not applicable" sentinel
inline constexpr double FUEL_ENGINE_EFFICIENCY = 0.30;
inline constexpr double FUEL_ALTERNATOR_EFFICIENCY = 0.50;
inline constexpr double DIESEL_J_PER_ML = 36000.0;
inline constexpr double PEUKERT_FACTOR_MIN = 0.5;
inline constexpr double PEUKERT_FACTOR_MAX = 2.0;
inline constexpr std::int64_t CRITICAL_ZONE_MS = 5000;  // field-off edge + 5 s checkpoint

// Added here (docs/batteries.md): battery temperature. A sample older than
// this is stale (the DS18B20 posts every second, a BMS about as often).
inline constexpr std::int64_t BATTERY_TEMP_STALE_MS = 20000;
// After start, a configured source has this long to post its first sample;
// until then a bank that needs its temperature is not charged at all.
inline constexpr std::int64_t BATTERY_TEMP_FIRST_SAMPLE_MS = 5000;
// DS18B20 measuring range (docs/sources.md D3); outside it a value is invalid.
inline constexpr double BATTERY_TEMP_VALID_MIN_C = -55.0;
inline constexpr double BATTERY_TEMP_VALID_MAX_C = 125.0;
// Hot stop resumes this far below ChargeMaxTempC (docs/batteries.md); the cold lockout
// releases this far above ChargeMinTempC (the current cap ramps from there).
inline constexpr double BATTERY_HOT_HYSTERESIS_C = 3.0;
inline constexpr double BATTERY_COLD_HYSTERESIS_C = 0.5;
// Without a temperature, a bank with BatteryTempRequired charges at C/10.
inline constexpr double BATTERY_NO_TEMP_RATE_C = 0.1;
// Lead-acid compensation is referred to 25 degC (docs/sources.md P3.7.1) and never
// raises a target closer than this to the hard-shutdown trip or the INA228
// limit (the same margin CVTuningMode keeps).
inline constexpr double TEMP_COMP_REFERENCE_C = 25.0;
inline constexpr double TEMP_COMP_TRIP_MARGIN_V = 0.2;

}  // namespace xr::k
