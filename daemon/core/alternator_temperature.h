#pragma once
// The alternator temperature the regulator acts on: which sensor
// (TempSource) and when a reading counts. One home for both, so the thermal
// derate, the temperature protections T1-T5 (docs/protections.md) and the
// auto-zero's temperature trigger cannot disagree about either.
#include "core/finite.h"
#include "core/inputs.h"
#include "core/time.h"
#include "params/constants.h"

namespace xr {

// TempSource 1: the thermistor on ADS1115 CH3; 0: the DS18B20 on 1-Wire.
inline const Reading& alternatorTemperature(const Inputs& in, int tempSource) noexcept {
  return tempSource == 1 ? in.thermistorF : in.AlternatorTemperatureF;
}

// Within what the sensors can read (TEMP_VALID_MIN_F..TEMP_VALID_MAX_F).
inline bool temperatureInRange(double degF) noexcept {
  return finite(degF) && degF >= k::TEMP_VALID_MIN_F && degF <= k::TEMP_VALID_MAX_F;
}

// Read at least once, in range, and no older than TEMP_STALE_MS at `now`.
inline bool temperatureFresh(double degF, TimeNs stamp, TimeNs now) noexcept {
  return stamp != 0 && temperatureInRange(degF) && now - stamp <= fromMs(k::TEMP_STALE_MS);
}

}  // namespace xr
