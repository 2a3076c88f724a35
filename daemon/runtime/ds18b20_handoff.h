#pragma once
// A DS18B20 sample as the control cycle's temperature hand-off: the value
// only when a valid reading exists, its stamp (T5) and the reader thread's
// heartbeat (T4, moves even when the reading is bad). One mapping for the
// board's 1 Hz thread, the daemon's --sim rig and the headless SimRunner.
#include "drivers/onewire/ds18b20_reader.h"
#include "runtime/handoffs.h"

namespace xr {

inline rt::TemperatureHandoff temperatureHandoff(const Ds18b20Sample& s) noexcept {
  rt::TemperatureHandoff th;
  th.tempF = s.stamp != 0 ? s.tempF : kNoValue;
  th.stamp = s.stamp;
  th.heartbeat = s.heartbeat;
  return th;
}

// The battery DS18B20 (docs/batteries.md): degC, source ds18b20 even before its first
// valid reading, so the core knows a sensor is expected.
inline rt::BatteryTempHandoff batteryTempHandoff(const Ds18b20Sample& s) noexcept {
  rt::BatteryTempHandoff bh;
  bh.tempC = s.stamp != 0 ? (s.tempF - 32.0) * 5.0 / 9.0 : kNoValue;
  bh.stamp = s.stamp;
  bh.source = BatteryTempSource::ds18b20;
  return bh;
}

}  // namespace xr
