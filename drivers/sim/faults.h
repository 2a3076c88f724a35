#pragma once
// Injectable faults (docs/simulator.md), named as in scenario files: fault = "<name>",
// with value = ... where one applies.
#include <optional>
#include <string_view>

namespace xr::sim {

enum class Fault {
  ina228_nack,             // INA228 stops acknowledging its address
  ads1115_nack,            // ADS1115 stops acknowledging its address
  battery_v_offset,        // V added to the CH0 battery-voltage sense
  battery_v_zero,          // CH0 reads 0 V (broken sense wire)
  ibv_offset,              // V added to the INA228 VBUS pin
  alt_current_offset,      // A added to the Hall sensor (zero drift)
  temp_sensor_disconnect,  // DS18B20 gone from the 1-Wire bus, thermistor open
  temp_value,              // temperature sensors read this fixed value, degF
  rpm_signal_loss,         // LM2907 input lost: output decays with its 2 s coupling
  field_open,              // field winding open: no field current whatever the duty
  belt_slip,               // the belt slips: value = the alternator's speed loss at rated output (0..0.9)
};
inline constexpr int kFaultCount = 11;

std::string_view toString(Fault f);
std::optional<Fault> parseFault(std::string_view name);
// True when the fault takes a `value` (offsets, fixed readings).
bool faultTakesValue(Fault f);

}  // namespace xr::sim
