// Plain names for the regulator's modes, stages and reasons, and the ONE
// table of what each reason means and what to do. docs/operations.md's
// reasons table is generated from REASONS (web/tools/reasons-doc.mjs; the
// web_reasons_doc ctest fails when the two differ or a Reason of
// daemon/core/modes.h has no row here).

// kind: "fault" (a protection acting: banner, alarm), "warn" (the regulator
// holds back on purpose: banner), "state" (normal, e.g. engine stopped: no
// alarm). flag: the /api/status protection flag that is true while it acts,
// so several active protections give several banners.
export const REASONS = {
  NONE: { title: "Nothing holding back", kind: "state", meaning: "", action: "", detail: "" },
  REASON_INA_OVERVOLTAGE: {
    title: "Battery over-voltage", kind: "fault", flag: "ina_overvoltage_latched",
    meaning: "The battery voltage went above the safe limit, so the hardware switched the alternator field off at once.",
    action: "Find why the voltage rose (a load dump, a BMS disconnect, a loose battery sense lead, a wrong bulk voltage) before charging again. The latch releases by itself once the voltage is normal.",
    detail: "Battery voltage crossed the INA228 hardware limit (BulkVoltage + 0.3 V); its ALERT pulled the field enable LOW and the software latch holds it off.",
  },
  REASON_HARD_OVERCURRENT: {
    title: "Alternator over-current", kind: "fault", flag: "hard_overcurrent",
    meaning: "The alternator gave far more current than its rating allows, so the field was cut at once.",
    action: "Check the alternator current sensor (zero and sensitivity), the field driver for a short, and that the alternator rating in the settings is right.",
    detail: "Alternator current above MaxTableValue + 10 A for HardOCDebounceMs: immediate cut in every mode.",
  },
  REASON_TEMP_CRITICAL: {
    title: "Alternator far too hot", kind: "fault", flag: "temp_critical",
    meaning: "The alternator is well above its temperature limit; charging stopped at once.",
    action: "Let it cool. Check belt tension, airflow and the temperature sensor's mounting; lower the current limits.",
    detail: "Alternator above TemperatureLimitF + TempCritExcess: immediate cut.",
  },
  REASON_TEMP_WARNING: {
    title: "Alternator too hot", kind: "fault", flag: "temp_warning",
    meaning: "The alternator is above its temperature limit even with reduced current; charging pauses and retries after a cooldown.",
    action: "Check belt and airflow; lower the alternator's current limit.",
    detail: "Above TemperatureLimitF + TempWarnExcess: warning ramp and lockout; the thermal derate was not enough.",
  },
  REASON_TEMP_SUSTAINED: {
    title: "Alternator stayed too hot", kind: "fault", flag: "temp_sustained",
    meaning: "The alternator stayed too hot for too long; charging stays off until you switch it back on.",
    action: "Fix the cooling, then press “Re-enable field” on the Protections page.",
    detail: "The warning condition lasted TempSustainedTimeout: field off until the reenable_field command.",
  },
  REASON_TEMP_STALE: {
    title: "Temperature sensor not answering", kind: "fault", flag: "temp_stale",
    meaning: "No valid alternator temperature for 20 s, so charging stopped: it cannot be done safely blind.",
    action: "Check the temperature sensor's wiring and connector (1-Wire data line and pull-up, or the thermistor), and the temperature source setting.",
    detail: "No valid temperature for 20 s (DS18B20 missing, 85 °C/CRC errors, thermistor open); check onewire_sensor_id and TempSource.",
  },
  REASON_CURRENT_STALE: {
    title: "Current sensor not answering", kind: "fault", flag: "current_stale",
    meaning: "The battery monitor or the alternator current sensor stopped answering, so the current shown is not live and charging stopped.",
    action: "Check the I2C wiring to the battery monitor (INA228) and the ADC (ADS1115): connectors, pull-ups, addresses. Run xregulatord --probe.",
    detail: "No fresh current sample (INA228 or ADS1115 CH1) for CurrentStaleMs.",
  },
  REASON_ALT_HARD_SHUTDOWN: {
    title: "Battery voltage too high", kind: "fault", flag: "alt_hard_shutdown",
    meaning: "The battery voltage rose above the shutdown limit; charging pauses and retries after a cooldown.",
    action: "As for over-voltage: look for a load dump or a wrong bulk voltage. If you changed the battery bank, check the shutdown voltage too.",
    detail: "Battery voltage above AlternatorHardShutdownV (saved on first boot as BulkVoltage + 0.3 V): warning ramp + lockout, instant above +0.5 V.",
  },
  REASON_VOLTAGE_DISAGREE_WARNING: {
    title: "Voltage sensors disagree", kind: "fault", flag: "voltage_disagree_warning",
    meaning: "The two battery voltage measurements differ; charging pauses and retries after a cooldown.",
    action: "Check both battery sense leads and the divider values in the hardware settings.",
    detail: "INA228 and ADS1115 battery voltages differ by more than VoltageDisagreeThreshold for VoltageDisagreeTimeout; check [hardware.frontend].",
  },
  REASON_VOLTAGE_DISAGREE_CRITICAL: {
    title: "Voltage sensors far apart", kind: "fault", flag: "voltage_disagree_critical",
    meaning: "The two battery voltage measurements are far apart (a lead is off or a sensor failed); charging stopped.",
    action: "Fix the sense wiring or the failed sensor before charging again.",
    detail: "They differ by 1/2/4 V (12/24/48 V system) for 3 s, or one reads about 0: critical ramp.",
  },
  REASON_VOLTAGE_IMPLAUSIBLE: {
    title: "Battery voltage makes no sense", kind: "fault", flag: "voltage_implausible",
    meaning: "A battery voltage is outside what a battery of this size can show; charging stopped.",
    action: "Check the voltage sensors, and that the bulk voltage matches your battery (12, 24 or 48 V).",
    detail: "A battery voltage outside the plausible range for the system class set by BulkVoltage.",
  },
  REASON_LOCKOUT: {
    title: "Cooling down after a shutdown", kind: "warn",
    meaning: "After a protection switched charging off, the regulator waits before it tries again.",
    action: "Nothing to do if the cause is gone; it restarts by itself. The cause is the event just before.",
    detail: "The FIELD_COLLAPSE_DELAY (30 s) cooldown after a shutdown is running.",
  },
  REASON_RPM_LOW: {
    title: "Engine stopped or idling", kind: "state",
    meaning: "The engine turns too slowly to charge.",
    action: "Normal with the engine off. If the engine runs, check the RPM signal wiring and the RPM settings.",
    detail: "Engine RPM below MinRPMForField; check the tach signal and rpm_per_volt.",
  },
  REASON_AUTO_ZERO: {
    title: "Re-zeroing the current sensor", kind: "state",
    meaning: "Charging pauses for a moment while the alternator current sensor is re-zeroed.",
    action: "Nothing; it resumes by itself.",
    detail: "Field off briefly while the Hall sensor is re-zeroed (AutoAltCurrentZero).",
  },
  REASON_IGNITION_OFF: {
    title: "Ignition off", kind: "state",
    meaning: "The ignition input says the engine is off.",
    action: "Normal. If the ignition is on, check the ignition wiring and its polarity setting.",
    detail: "The ignition input says off; check ignition_line and its polarity.",
  },
  REASON_ONOFF_DISABLED: {
    title: "Charging switched off in the settings", kind: "state",
    meaning: "The on/off setting is off.",
    action: "Switch “OnOff” back on, or press Auto.",
    detail: "OnOff is 0: charging switched off by the user.",
  },
  REASON_BMS_DISABLED: {
    title: "Battery management asks to stop", kind: "warn",
    meaning: "The battery's management system asked to stop charging.",
    action: "Check the BMS (full, cold or protecting its cells), and the BMS input polarity setting.",
    detail: "The BMS input asks to stop charging; check bms_active_low.",
  },
  // Battery temperature limits (docs/batteries.md): listed here so
  // the banner and docs/operations.md have them once that branch is merged.
  REASON_BATTERY_COLD: {
    title: "Battery too cold to charge", kind: "warn",
    meaning: "The battery is below its lowest charging temperature (0 °C for LiFePO4), so charging waits.",
    action: "Nothing; it resumes when the bank warms, with a gentle current at first. Heat the space if it stays cold.",
    detail: "Battery below ChargeMinTempC: no charging; resumes 0.5 °C above it, ramping the current up to ChargeFullCurrentTempC (docs/batteries.md).",
  },
  REASON_BATTERY_HOT: {
    title: "Battery too hot to charge", kind: "warn",
    meaning: "The battery is above its highest charging temperature, so charging waits until it is 3 °C cooler.",
    action: "Ventilate the battery space; check where the battery temperature sensor sits.",
    detail: "Battery above ChargeMaxTempC: no charging until 3 °C below it.",
  },
  REASON_TEMP_SOAK: {
    title: "Alternator cooling after the engine stop", kind: "warn",
    meaning: "The engine restarted while the alternator was still hot from its last run (heat soaks into the case once the engine and its fan stop), so the field stays off until the running fan has cooled it.",
    action: "Nothing; charging resumes by itself once the alternator is back under its temperature limit, usually within minutes.",
    detail: "Engine restarted above TemperatureLimitF: field off until TempToUse <= TemperatureLimitF; T1/T2 do not count the engine-off soak (docs/deviations.md).",
  },
  REASON_BANK_MISMATCH: {
    title: "Settings are for another bank size", kind: "fault", flag: "bank_mismatch",
    meaning: "The battery measures a different bank size (12, 24 or 48 V) than the charging voltages are set for, so every charging limit would be wrong. The field is off.",
    action: "Set the charging voltages for this bank (a battery profile on the set-up page, or the [voltage] values in the configuration file), then charging starts by itself.",
    detail: "Every live voltage sensor read another bank class (below 18 V, 18 to 36 V, above 36 V) than BulkVoltage for 5 s: immediate cut in every mode until they agree (docs/deviations.md).",
  },
  REASON_BMS_STALE: {
    title: "Battery management silent", kind: "warn",
    meaning: "The battery's management system stopped sending its charge limits, so charging continues at a reduced, safe current.",
    action: "Check the CAN cable and termination to the BMS, and that the BMS is switched on. Charging returns to normal when its limits come back.",
    detail: "No BMS limits for BmsStaleS: alternator current capped at BmsFallbackCapA (docs/integrations.md, CAN).",
  },
  REASON_WEATHER_MODE: {
    title: "Weather mode: solar first", kind: "state",
    meaning: "Weather mode leaves charging to the solar panels today.",
    action: "Normal while weather mode is on; switch it off to charge from the engine.",
    detail: "Weather mode (solar priority) disabled charging; weatherModeEnabled = 0 stops it.",
  },
  REASON_IDLE_STAGE: {
    title: "Battery full, resting", kind: "state",
    meaning: "Charging finished and float is not used, so the alternator rests.",
    action: "Nothing; it charges again when the battery needs it.",
    detail: "Charging finished with UseFloat = 0: idle, field off; re-bulks on voltage sag or discharge.",
  },
  REASON_SYS_OFF: {
    title: "Switched off", kind: "state",
    meaning: "You switched the regulator off.",
    action: "Press Auto to charge again.",
    detail: "The regulator was switched off (off command).",
  },
  REASON_LIMP_HOME: {
    title: "Limp home", kind: "warn",
    meaning: "A fixed, low field with most sensors ignored, to get home with a failed sensor.",
    action: "Watch the battery voltage yourself. Switch limp home off as soon as the sensor is fixed.",
    detail: "Limp-home mode: fixed duty, most sensors ignored; limp_home_off ends it.",
  },
  REASON_SYSTEM_ID: {
    title: "Measuring the alternator", kind: "state",
    meaning: "The step test that measures how the alternator responds is running.",
    action: "Nothing; it ends by itself.",
    detail: "The plant step test (SystemID) is running.",
  },
};

export const reasonInfo = (code) =>
  REASONS[code] || { title: String(code || "—"), kind: "fault", meaning: "", action: "", detail: "" };

export const STAGES = { BULK: "Bulk", ABSORPTION: "Absorption", FLOAT: "Float", IDLE: "Resting" };

// What the owner chose (SysMode) in one word; the field-control mode below.
export const SYS_MODES = { SYS_MODE_OFF: "Off", SYS_MODE_MANUAL: "Manual", SYS_MODE_AUTO: "Auto", SYS_MODE_FAULT: "Fault" };
export const MODES = {
  MODE_NORMAL_AUTO_PID: "Auto",
  MODE_NORMAL_MANUAL: "Manual",
  MODE_LIMP_HOME: "Limp home",
  MODE_CRITICAL_RAMP: "Shutting down (fault)",
  MODE_WARNING_RAMP_AND_LOCKOUT: "Pausing (protection)",
  MODE_LOCKOUT_RAMP: "Cooling down",
  MODE_DISABLED_RAMP: "Switching off",
};
// The commands (POST /api/commands) as their buttons say them.
export const COMMANDS = { auto: "Auto", manual: "Manual", off: "Off", limp_home: "Limp home", limp_home_off: "Limp home off",
  reenable_field: "Re-enable field", reset_alarm_latch: "Reset alarm latch", acknowledge_alarm: "Acknowledge alarm", reset_soc_gain: "Reset SoC gain",
  reset_alt_zero: "Reset alternator zero", set_soc: "Set SoC", system_id_start: "Start SystemID",
  tuning_commit: "Commit current-loop tuning", cv_tuning_commit: "Commit voltage-loop tuning", weather_mode: "Weather mode" };
export const plainCommand = (c) => COMMANDS[c] || String(c || "—").replace(/_/g, " ");
// The regulator's answer to a command ("applied: limp_home", "tuning_commit
// refused by the regulator: ...") in words, without the command's API name.
export function commandAnswer(message) {
  const m = String(message || "");
  if (/^applied\b/.test(m)) return "done";
  if (/^queued\b/.test(m)) return "sent; the regulator has not answered yet";
  const refused = m.match(/refused by the regulator: (.*)$/);
  if (refused) return "refused — " + refused[1];
  return m.replace(/\b[a-z]+(?:_[a-z]+)+\b/g, (c) => (COMMANDS[c] ? `“${COMMANDS[c]}”` : c));
}
export const plainStage = (s) => STAGES[s] || String(s || "—");
export const plainMode = (m) => MODES[m] || String(m || "—");

// The mode the owner sees in the header: Off / Manual / Auto / Limp home.
// "Off" only when someone switched it off: a weather hold, a resting bank
// or a heat soak also park the control law in SYS_MODE_OFF, but the owner's
// choice is still Auto, waiting (a weather hold reads "Solar first", as its
// headline). These reasons come after the operator's Off in the regulator's
// order (docs/protections.md), so they never hide it.
const AUTO_WAITING = { REASON_WEATHER_MODE: "Solar first", REASON_IDLE_STAGE: "Auto", REASON_TEMP_SOAK: "Auto" };
export function ownerMode(s) {
  if (s.mode === "MODE_LIMP_HOME") return "Limp home";
  const sys = s.control && s.control.sys_mode;
  if (AUTO_WAITING[s.reason] && (!sys || sys === "SYS_MODE_OFF" || sys === "SYS_MODE_AUTO")) return AUTO_WAITING[s.reason];
  if (sys && SYS_MODES[sys]) return SYS_MODES[sys];
  return plainMode(s.mode);
}

const on = (v) => v === true || v === 1;

// Every protection acting now, each once: the flags in the protection
// section, then the reason the regulator names, when it is not normal.
export function activeProblems(s) {
  const p = s.protection || {};
  const list = [];
  for (const [code, r] of Object.entries(REASONS)) if (r.flag && on(p[r.flag])) list.push(code);
  const acting = s.reason;
  if (acting && acting !== "NONE" && !list.includes(acting) && reasonInfo(acting).kind !== "state") list.push(acting);
  return list;
}
