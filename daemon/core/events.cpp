#include "core/events.h"

#include <cstdio>

namespace xr {

std::string_view toString(EventLevel l) {
  switch (l) {
    case EventLevel::Debug: return "debug";
    case EventLevel::Info: return "info";
    case EventLevel::Warning: return "warning";
    case EventLevel::Error: return "error";
    case EventLevel::Critical: return "critical";
  }
  return "?";
}

std::string_view toString(EventCode c) {
  switch (c) {
    case EventCode::ModeChanged: return "ModeChanged";
    case EventCode::ProtectionTrip: return "ProtectionTrip";
    case EventCode::ProtectionClear: return "ProtectionClear";
    case EventCode::ImmediateCut: return "ImmediateCut";
    case EventCode::CutAfterSettle: return "CutAfterSettle";
    case EventCode::LockoutStarted: return "LockoutStarted";
    case EventCode::LockoutExpired: return "LockoutExpired";
    case EventCode::StageChanged: return "StageChanged";
    case EventCode::FieldOn: return "FieldOn";
    case EventCode::FieldOff: return "FieldOff";
    case EventCode::InaLatchSet: return "InaLatchSet";
    case EventCode::InaLatchCleared: return "InaLatchCleared";
    case EventCode::VoltageDisagreement: return "VoltageDisagreement";
    case EventCode::TempSensorStale: return "TempSensorStale";
    case EventCode::TempTaskHung: return "TempTaskHung";
    case EventCode::AlarmOn: return "AlarmOn";
    case EventCode::AlarmOff: return "AlarmOff";
    case EventCode::LimpHomeActive: return "LimpHomeActive";
    case EventCode::FullChargeDetected: return "FullChargeDetected";
    case EventCode::ShuntGainCorrected: return "ShuntGainCorrected";
    case EventCode::AutoZeroStarted: return "AutoZeroStarted";
    case EventCode::AutoZeroDone: return "AutoZeroDone";
    case EventCode::SystemIdDone: return "SystemIdDone";
    case EventCode::TuningCommitted: return "TuningCommitted";
    case EventCode::CommandApplied: return "CommandApplied";
    case EventCode::CommandRejected: return "CommandRejected";
    case EventCode::Message: return "Message";
  }
  return "?";
}

std::string describe(const Event& e) {
  char buf[256];
  const std::string reason{toString(e.reason)};
  switch (e.code) {
    case EventCode::ModeChanged:
      if (e.mode == FieldControlMode::MODE_NORMAL_AUTO_PID || e.mode == FieldControlMode::MODE_NORMAL_MANUAL)
        return "Entering normal mode";
      return "Exiting normal mode: " + reason;
    case EventCode::ImmediateCut: return "GPIO4 immediate cut: " + reason;
    case EventCode::CutAfterSettle: return "GPIO4 cut after settle: " + reason;
    case EventCode::LockoutStarted:
      std::snprintf(buf, sizeof buf, "Field lockout started: %.0fs cooldown before restart allowed", e.a);
      return buf;
    case EventCode::LockoutExpired: return "Field lockout expired - normal operation resumed";
    case EventCode::StageChanged:
      if (static_cast<ChargeStage>(static_cast<int>(e.b)) == ChargeStage::BULK) return "CHARGING: Returning to bulk stage";
      std::snprintf(buf, sizeof buf, "CHARGING: %s stage complete, switching to %s",
                    std::string(toString(static_cast<ChargeStage>(static_cast<int>(e.a)))).c_str(),
                    std::string(toString(static_cast<ChargeStage>(static_cast<int>(e.b)))).c_str());
      return buf;
    case EventCode::VoltageDisagreement:
      std::snprintf(buf, sizeof buf,
                    "Battery Voltage disagreement! BatteryV=%.2f V, IBV=%.2f V. Field shut off for safety!", e.a,
                    e.b);
      return buf;
    case EventCode::TempSensorStale: return "OneWire sensor stale, sensor dead or disconnected";
    default:
      std::snprintf(buf, sizeof buf, "%s %s a=%.3f b=%.3f", std::string(toString(e.code)).c_str(), reason.c_str(),
                    e.a, e.b);
      return buf;
  }
}

}  // namespace xr
