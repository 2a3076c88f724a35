#include "drivers/sim/faults.h"

#include <array>

namespace xr::sim {
namespace {
struct FaultName {
  Fault f;
  std::string_view name;
  bool value;
};
constexpr std::array<FaultName, kFaultCount> kFaults{{
    {Fault::ina228_nack, "ina228_nack", false},
    {Fault::ads1115_nack, "ads1115_nack", false},
    {Fault::battery_v_offset, "battery_v_offset", true},
    {Fault::battery_v_zero, "battery_v_zero", false},
    {Fault::ibv_offset, "ibv_offset", true},
    {Fault::alt_current_offset, "alt_current_offset", true},
    {Fault::temp_sensor_disconnect, "temp_sensor_disconnect", false},
    {Fault::temp_value, "temp_value", true},
    {Fault::rpm_signal_loss, "rpm_signal_loss", false},
    {Fault::field_open, "field_open", false},
    {Fault::belt_slip, "belt_slip", true},
}};
}  // namespace

std::string_view toString(Fault f) {
  for (const auto& x : kFaults)
    if (x.f == f) return x.name;
  return "?";
}
std::optional<Fault> parseFault(std::string_view name) {
  for (const auto& x : kFaults)
    if (x.name == name) return x.f;
  return std::nullopt;
}
bool faultTakesValue(Fault f) {
  for (const auto& x : kFaults)
    if (x.f == f) return x.value;
  return false;
}

}  // namespace xr::sim
