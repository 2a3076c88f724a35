#include "core/events.h"

#include <cstddef>
#include <cstdio>
#include <iterator>
#include <optional>
#include <string>

#include "core/bms_limits.h"
#include "core/calm_text.h"
#include "core/charge_checks.h"
#include "core/commands.h"

namespace xr {

std::string_view toString(EventLevel l) {
  switch (l) {
    case EventLevel::Debug:
      return "debug";
    case EventLevel::Info:
      return "info";
    case EventLevel::Warning:
      return "warning";
    case EventLevel::Error:
      return "error";
    case EventLevel::Critical:
      return "critical";
  }
  return "?";
}

// The names, in the order of EventCode (the static_assert keeps them in step).
constexpr std::string_view kEventCodeNames[] = {
    "ModeChanged",
    "ProtectionTrip",
    "ProtectionClear",
    "ImmediateCut",
    "CutAfterSettle",
    "LockoutStarted",
    "LockoutExpired",
    "StageChanged",
    "FieldOn",
    "FieldOff",
    "InaLatchSet",
    "InaLatchCleared",
    "VoltageDisagreement",
    "TempSensorStale",
    "TempTaskHung",
    "AlarmOn",
    "AlarmOff",
    "LimpHomeActive",
    "FullChargeDetected",
    "ShuntGainCorrected",
    "AutoZeroStarted",
    "AutoZeroDone",
    "SystemIdDone",
    "TuningCommitted",
    "CommandApplied",
    "CommandRejected",
    "Message",
    "AlarmCondition",
    "BatteryTempMissing",
    "BatteryTempBack",
    "BmsBadFrames",
    "CanBusDown",
    "CanBusBack",
    "CanErrorFrames",
    "WeatherForecastMissing",
    "WeatherForecastBack",
    "CapacityMeasured",
    "BeltSlip",
    "BmsMismatch",
    "ChargingHeld",
};
static_assert(std::size(kEventCodeNames) == static_cast<std::size_t>(kEventCodeCount));

std::string_view toString(EventCode c) {
  const auto i = static_cast<std::size_t>(c);
  return i < std::size(kEventCodeNames) ? kEventCodeNames[i] : "?";
}

namespace {

std::string weatherMissingText(WeatherMissing w, double httpStatus) {
  switch (w) {
    case WeatherMissing::NoPosition:
      return "no position: none from the boat, none in the file";
    case WeatherMissing::ServerError:
      return "the server answered HTTP " + std::to_string(int(httpStatus));
    case WeatherMissing::NoAnswer:
      return "no answer from the server";
    case WeatherMissing::AnswerRefused:
      return "the answer is not a forecast";
  }
  return "?";
}

// Reason as the specification's console lines print it: "TEMP_CRITICAL", not "REASON_TEMP_CRITICAL".
std::string shortReason(Reason r) {
  std::string s{toString(r)};
  constexpr std::string_view prefix = "REASON_";
  if (s.rfind(prefix, 0) == 0) s.erase(0, prefix.size());
  return s;
}

std::string tripText(const Event& e, char* buf, std::size_t n) {
  switch (e.reason) {
    case Reason::REASON_HARD_OVERCURRENT:
      std::snprintf(buf, n, "Hard overcurrent: %.1f A > %.1f A trip. Field shut off!", e.a, e.b);
      return buf;
    case Reason::REASON_TEMP_CRITICAL:
      std::snprintf(buf, n, "Temperature critical: %.1f F > %.1f F. Field shut off!", e.a, e.b);
      return buf;
    case Reason::REASON_TEMP_WARNING:
      std::snprintf(buf, n, "Temperature warning: %.1f F > %.1f F. Ramping field down", e.a, e.b);
      return buf;
    case Reason::REASON_TEMP_SUSTAINED:
      std::snprintf(buf, n, "Temperature warning sustained: %.1f F > %.1f F. Field off until re-enabled", e.a,
                    e.b);
      return buf;
    case Reason::REASON_ALT_HARD_SHUTDOWN:
      std::snprintf(buf, n, "Alternator hard shutdown: IBV=%.2f V > %.2f V. Ramping field down", e.a, e.b);
      return buf;
    case Reason::REASON_BATTERY_COLD:
      std::snprintf(buf, n, "Battery too cold to charge: %.1f C < %.1f C. Field off until it warms", e.a,
                    e.b);
      return buf;
    case Reason::REASON_BATTERY_HOT:
      std::snprintf(buf, n, "Battery too hot to charge: %.1f C > %.1f C. Field off until 3 C cooler", e.a,
                    e.b);
      return buf;
    case Reason::REASON_TEMP_SOAK:
      std::snprintf(buf, n, "Alternator hot after an engine stop: %.1f F > %.1f F. Field off until it cools",
                    e.a, e.b);
      return buf;
    case Reason::REASON_BANK_MISMATCH:
      std::snprintf(buf, n,
                    "Battery reads %.1f V but the settings are for a %.0f V bank (BulkVoltage). Field off "
                    "until they match",
                    e.a, e.b);
      return buf;
    case Reason::REASON_RPM_LOW:
      std::snprintf(buf, n, "RPM below minimum: %.0f < %.0f RPM. Field off", e.a, e.b);
      return buf;
    case Reason::REASON_VOLTAGE_IMPLAUSIBLE:
      std::snprintf(buf, n,
                    "Battery voltage implausible: IBV=%.2f V, BatteryV=%.2f V. Field shut off for safety!",
                    e.a, e.b);
      return buf;
    case Reason::REASON_CURRENT_STALE:
      std::snprintf(buf, n, "Current data stale (CH1 %s, INA228 %s). Field shut off for safety!",
                    e.a != 0.0 ? "stale" : "ok", e.b != 0.0 ? "stale" : "ok");
      return buf;
    default:
      return "Protection tripped: " + shortReason(e.reason);
  }
}

const char* alarmRowText(int row) {
  // Order of protection/alarm_rows.h (the specification's buzzer table).
  static constexpr const char* kRows[] = {"High alternator temperature",
                                          "Low alternator temperature",
                                          "High battery voltage",
                                          "Low battery voltage",
                                          "High alternator current",
                                          "High battery current",
                                          "INA228 hardware overvoltage",
                                          "Temp sensor not responding",
                                          "Efficiency anomaly",
                                          "Field protection active",
                                          "TempTask hung",
                                          "BMS limits stale",
                                          "BMS does not fit the bank",
                                          "Charging held"};
  if (row < 0 || row >= static_cast<int>(sizeof kRows / sizeof kRows[0])) return "Alarm";
  return kRows[row];
}

}  // namespace

namespace {

// Modes, protections, the lockout and the charging stage.
std::optional<std::string> describeModeAndStage(const Event& e) {
  char buf[256];
  const std::string reason = shortReason(e.reason);
  switch (e.code) {
    case EventCode::ModeChanged:
      if (e.mode == FieldControlMode::MODE_NORMAL_AUTO_PID ||
          e.mode == FieldControlMode::MODE_NORMAL_MANUAL || e.mode == FieldControlMode::MODE_LIMP_HOME)
        return "Entering normal mode";
      if (e.detail == 1) return "Mode changed: " + std::string(toString(e.mode)) + " (" + reason + ")";
      return "Exiting normal mode: " + reason;
    case EventCode::ProtectionTrip:
      return tripText(e, buf, sizeof buf);
    case EventCode::ProtectionClear:
      return "Protection cleared: " + reason;
    case EventCode::ImmediateCut:
      return "GPIO4 immediate cut: " + reason;
    case EventCode::CutAfterSettle:
      return "GPIO4 cut after settle: " + reason;
    case EventCode::LockoutStarted:
      std::snprintf(buf, sizeof buf, "Field lockout started: %.0fs cooldown before restart allowed", e.a);
      return buf;
    case EventCode::LockoutExpired:
      return "Field lockout expired - normal operation resumed";
    case EventCode::StageChanged:
      if (static_cast<ChargeStage>(static_cast<int>(e.b)) == ChargeStage::BULK)
        return "CHARGING: Returning to bulk stage";
      std::snprintf(buf, sizeof buf, "CHARGING: %s stage complete, switching to %s",
                    std::string(toString(static_cast<ChargeStage>(static_cast<int>(e.a)))).c_str(),
                    std::string(toString(static_cast<ChargeStage>(static_cast<int>(e.b)))).c_str());
      return buf;
    default:
      return std::nullopt;
  }
}

// Sensor faults, alarms, the field enable and limp home.
std::optional<std::string> describeSensorsAndField(const Event& e) {
  char buf[256];
  switch (e.code) {
    case EventCode::InaLatchSet:
      std::snprintf(buf, sizeof buf,
                    "INA228 hardware overvoltage alert: IBV=%.2f V (limit %.2f V). Field cut, latched", e.a,
                    e.b);
      return buf;
    case EventCode::InaLatchCleared:
      std::snprintf(buf, sizeof buf, "INA228 overvoltage latch cleared after %.0f s", e.b);
      return buf;
    case EventCode::VoltageDisagreement:
      std::snprintf(buf, sizeof buf,
                    "Battery Voltage disagreement! BatteryV=%.2f V, IBV=%.2f V. Field shut off for safety!",
                    e.a, e.b);
      return buf;
    case EventCode::TempSensorStale:
      return "OneWire sensor stale, sensor dead or disconnected";
    case EventCode::TempTaskHung:
      std::snprintf(buf, sizeof buf, "TempTask hung: no heartbeat for %.0f s. Alarm on", e.a);
      return buf;
    case EventCode::AlarmOn:
      return "Alarm ON";
    case EventCode::AlarmOff:
      return "Alarm OFF";
    case EventCode::AlarmCondition:
      std::snprintf(buf, sizeof buf, "ALARM: %s (%.2f, limit %.2f)", alarmRowText(e.detail), e.a, e.b);
      return buf;
    case EventCode::FieldOn:
      return "Field enabled (GPIO4 HIGH)";
    case EventCode::FieldOff:
      return e.reason == Reason::NONE ? std::string("Field disabled (GPIO4 LOW)")
                                      : "Field disabled (GPIO4 LOW): " + shortReason(e.reason);
    case EventCode::LimpHomeActive:
      std::snprintf(buf, sizeof buf, "LIMP HOME active: fixed %.0f %% duty, only the INA228 latch protects",
                    e.a);
      return buf;
    default:
      return std::nullopt;
  }
}

// Operator commands and the battery's own events.
std::optional<std::string> describeCommandsAndBattery(const Event& e) {
  char buf[256];
  switch (e.code) {
    case EventCode::CommandApplied:
    case EventCode::CommandRejected:
    case EventCode::TuningCommitted: {
      // The argument travels in a (duty or SoC %); the event list shows it (docs/dashboard.md).
      const auto type = static_cast<CommandType>(e.detail);
      const std::string_view arg = commandArgument(type);
      char args[48] = "";
      if (arg == "duty" || arg == "soc_pct")
        std::snprintf(args, sizeof args, " (%s %.1f %%)", arg == "duty" ? "duty" : "SoC", e.a);
      std::snprintf(buf, sizeof buf, "Command %s%s %s", std::string(toString(type)).c_str(), args,
                    e.code == EventCode::CommandRejected ? "rejected (not allowed now)" : "applied");
      return buf;
    }
    case EventCode::FullChargeDetected:
      std::snprintf(buf, sizeof buf, "Full charge detected: SoC set to 100 %% (%.1f Ah)", e.b);
      return buf;
    case EventCode::ShuntGainCorrected:
      std::snprintf(buf, sizeof buf, "Shunt gain factor %.4f (was %.4f)", e.a, e.b);
      return buf;
    case EventCode::AutoZeroStarted:
      return e.detail ? "Auto-zero of alternator current started (temperature shift): field off"
                      : "Auto-zero of alternator current started (scheduled): field off";
    case EventCode::BatteryTempMissing:
      if (e.detail == 1) {
        std::snprintf(buf, sizeof buf,
                      "Battery temperature missing or stale: charge current capped at C/10 (%.1f A) "
                      "(BatteryTempRequired)",
                      e.a);
        return buf;
      }
      return "Battery temperature missing or stale: charging without temperature compensation";
    case EventCode::BatteryTempBack:
      std::snprintf(buf, sizeof buf, "Battery temperature back: %.1f C", e.a);
      return buf;
    case EventCode::CapacityMeasured:
      std::snprintf(buf, sizeof buf, "Battery capacity measured: %.0f Ah over a %.0f %% swing (%d so far)",
                    e.a, e.b, e.detail);
      return buf;
    case EventCode::BeltSlip:
      if (e.detail == 1)
        std::snprintf(
            buf, sizeof buf,
            "Alternator belt slipping: the alternator turns %.0f %% slower than the engine (%.0f rpm). "
            "Check the belt's tension, wear and glazing, and the pulleys' alignment",
            e.a, e.b);
      else if (e.detail == 3)
        std::snprintf(buf, sizeof buf,
                      "Alternator belt slipping: the alternator sped up %.0f %% when its current was held "
                      "low (from %.0f A), and slowed again when it came back. Check the belt's tension, wear "
                      "and glazing, and the pulleys' alignment",
                      e.a, e.b);
      else
        std::snprintf(
            buf, sizeof buf,
            "Alternator belt slipping: current fell %.0f A while the field rose %.0f points at steady "
            "speed. Check the belt's tension, wear and glazing, and the pulleys' alignment",
            e.a, e.b);
      return buf;
    default:
      return std::nullopt;
  }
}

// The CAN buses, the forecast and the auto-zero's result.
std::optional<std::string> describeLinks(const Event& e) {
  char buf[256];
  switch (e.code) {
    case EventCode::BmsBadFrames:
      std::snprintf(buf, sizeof buf, "BMS CAN: %.0f bad frame(s) ignored (last: 0x%03X, %s)", e.a,
                    static_cast<unsigned>(e.b),
                    std::string(bmsRejectText(static_cast<BmsReject>(e.detail))).c_str());
      return buf;
    case EventCode::CanBusDown:
      std::snprintf(buf, sizeof buf,
                    "CAN %s bus cannot be opened (%.0f failed attempt(s)); retry in %.0f s%s",
                    e.detail == 0 ? "BMS" : "NMEA 2000", e.a, e.b,
                    e.detail == 0 ? ": the BMS limits go stale" : ": no NMEA 2000 output");
      return buf;
    case EventCode::CanBusBack:
      std::snprintf(buf, sizeof buf, "CAN %s bus open again after %.0f failed attempt(s)",
                    e.detail == 0 ? "BMS" : "NMEA 2000", e.a);
      return buf;
    case EventCode::CanErrorFrames:
      std::snprintf(buf, sizeof buf, "CAN %s bus: %.0f error frame(s) (last error class 0x%X)",
                    e.detail == 0 ? "BMS" : "NMEA 2000", e.a, static_cast<unsigned>(e.b));
      return buf;
    case EventCode::WeatherForecastMissing:
      std::snprintf(buf, sizeof buf,
                    "Weather forecast cannot be read (%s); next try in %.0f s. Without a "
                    "forecast younger than 24 h the alternator charges as usual",
                    weatherMissingText(static_cast<WeatherMissing>(e.detail), e.a).c_str(), e.b);
      return buf;
    case EventCode::WeatherForecastBack:
      return "Weather forecast read again: weather mode follows it";
    case EventCode::AutoZeroDone:
      std::snprintf(buf, sizeof buf, "Auto-zero done: DynamicAltCurrentZero %.3f A from %.0f samples%s", e.a,
                    e.b, e.detail ? " (rejected, offset kept)" : "");
      return buf;
    default:
      return std::nullopt;
  }
}

}  // namespace

std::string describe(const Event& e) {
  for (const auto part : {describeModeAndStage, describeSensorsAndField, describeCommandsAndBattery,
                          describeLinks, describeChargeChecks})
    if (auto text = part(e)) return calmNonFinite(std::move(*text));
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s %s a=%.3f b=%.3f", std::string(toString(e.code)).c_str(),
                shortReason(e.reason).c_str(), e.a, e.b);
  return calmNonFinite(buf);
}

}  // namespace xr
