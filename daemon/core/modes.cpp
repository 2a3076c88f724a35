#include "core/modes.h"

#include <array>
#include <utility>

namespace xr {
namespace {

template <typename E, std::size_t N>
std::string_view lookup(const std::array<std::pair<E, std::string_view>, N>& table, E v) {
  for (const auto& [e, s] : table)
    if (e == v) return s;
  return "?";
}

template <typename E, std::size_t N>
std::optional<E> reverse(const std::array<std::pair<E, std::string_view>, N>& table, std::string_view s) {
  for (const auto& [e, name] : table)
    if (name == s) return e;
  return std::nullopt;
}

#define XR_NAME(E, v)             \
  std::pair {                     \
    E::v, std::string_view { #v } \
  }

constexpr std::array kModes{
    XR_NAME(FieldControlMode, MODE_CRITICAL_RAMP), XR_NAME(FieldControlMode, MODE_WARNING_RAMP_AND_LOCKOUT),
    XR_NAME(FieldControlMode, MODE_LOCKOUT_RAMP),  XR_NAME(FieldControlMode, MODE_DISABLED_RAMP),
    XR_NAME(FieldControlMode, MODE_NORMAL_MANUAL), XR_NAME(FieldControlMode, MODE_NORMAL_AUTO_PID),
    XR_NAME(FieldControlMode, MODE_LIMP_HOME),
};
constexpr std::array kStages{
    XR_NAME(ChargeStage, BULK),
    XR_NAME(ChargeStage, ABSORPTION),
    XR_NAME(ChargeStage, FLOAT),
    XR_NAME(ChargeStage, IDLE),
};
constexpr std::array kSysModes{
    XR_NAME(SysMode, SYS_MODE_OFF),
    XR_NAME(SysMode, SYS_MODE_MANUAL),
    XR_NAME(SysMode, SYS_MODE_AUTO),
    XR_NAME(SysMode, SYS_MODE_FAULT),
};
constexpr std::array kGovModes{
    XR_NAME(GovMode, GOV_NORMAL_SLEW),
    XR_NAME(GovMode, GOV_BYPASS_SLEW),
    XR_NAME(GovMode, GOV_HOLD),
};
constexpr std::array kPhases{
    XR_NAME(ShutdownPhase, PHASE_NONE), XR_NAME(ShutdownPhase, PHASE_1), XR_NAME(ShutdownPhase, PHASE_2),
    XR_NAME(ShutdownPhase, PHASE_3),    XR_NAME(ShutdownPhase, PHASE_4), XR_NAME(ShutdownPhase, PHASE_DONE),
};
constexpr std::array kReasons{
    XR_NAME(Reason, NONE),
    XR_NAME(Reason, REASON_INA_OVERVOLTAGE),
    XR_NAME(Reason, REASON_HARD_OVERCURRENT),
    XR_NAME(Reason, REASON_TEMP_CRITICAL),
    XR_NAME(Reason, REASON_RPM_LOW),
    XR_NAME(Reason, REASON_ALT_HARD_SHUTDOWN),
    XR_NAME(Reason, REASON_VOLTAGE_DISAGREE_WARNING),
    XR_NAME(Reason, REASON_VOLTAGE_DISAGREE_CRITICAL),
    XR_NAME(Reason, REASON_VOLTAGE_IMPLAUSIBLE),
    XR_NAME(Reason, REASON_TEMP_WARNING),
    XR_NAME(Reason, REASON_TEMP_SUSTAINED),
    XR_NAME(Reason, REASON_TEMP_STALE),
    XR_NAME(Reason, REASON_CURRENT_STALE),
    XR_NAME(Reason, REASON_LOCKOUT),
    XR_NAME(Reason, REASON_AUTO_ZERO),
    XR_NAME(Reason, REASON_IGNITION_OFF),
    XR_NAME(Reason, REASON_ONOFF_DISABLED),
    XR_NAME(Reason, REASON_BMS_DISABLED),
    XR_NAME(Reason, REASON_WEATHER_MODE),
    XR_NAME(Reason, REASON_IDLE_STAGE),
    XR_NAME(Reason, REASON_SYS_OFF),
    XR_NAME(Reason, REASON_LIMP_HOME),
    XR_NAME(Reason, REASON_SYSTEM_ID),
    XR_NAME(Reason, REASON_BMS_STALE),
    XR_NAME(Reason, REASON_BATTERY_COLD),
    XR_NAME(Reason, REASON_BATTERY_HOT),
    XR_NAME(Reason, REASON_TEMP_SOAK),
    XR_NAME(Reason, REASON_BANK_MISMATCH),
};
#undef XR_NAME

}  // namespace

std::string_view toString(FieldControlMode m) { return lookup(kModes, m); }
std::string_view toString(ChargeStage s) { return lookup(kStages, s); }
std::string_view toString(SysMode m) { return lookup(kSysModes, m); }
std::string_view toString(GovMode m) { return lookup(kGovModes, m); }
std::string_view toString(ShutdownPhase p) { return lookup(kPhases, p); }
std::string_view toString(Reason r) { return lookup(kReasons, r); }
std::optional<FieldControlMode> parseFieldControlMode(std::string_view s) { return reverse(kModes, s); }
std::optional<ChargeStage> parseChargeStage(std::string_view s) { return reverse(kStages, s); }
std::optional<Reason> parseReason(std::string_view s) { return reverse(kReasons, s); }

}  // namespace xr
