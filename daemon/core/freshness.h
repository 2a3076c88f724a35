#pragma once
// When a reading may be used: one rule per input, in one place, so that the
// protections, the stages, the SoC counter and the health estimators cannot
// disagree about how old a sample may be (docs/architecture.md "Freshness").
// Every consumer calls these; a literal maximum age anywhere else in the core
// is refused by the layout check (tests/layout/freshness_rule.py).
#include <cstdint>

#include "core/alternator_temperature.h"
#include "core/finite.h"
#include "core/inputs.h"
#include "core/time.h"
#include "params/constants.h"

namespace xr::fresh {

// A reading with a value, taken no longer than maxAge before `now`.
inline bool within(const Reading& r, TimeNs now, TimeNs maxAge) noexcept {
  return finite(r.value) && r.stamp != 0 && now - r.stamp <= maxAge;
}
inline bool withinMs(const Reading& r, TimeNs now, std::int64_t maxAgeMs) noexcept {
  return within(r, now, fromMs(maxAgeMs));
}

// The alternator temperature the protections, the derate and the wear count
// act on: in the sensors' range and no older than TEMP_STALE_MS.
inline bool alternatorTemp(const Reading& r, TimeNs now) noexcept {
  return temperatureFresh(r.value, r.stamp, now);
}

// The battery temperature: in the DS18B20's range and no older than
// BATTERY_TEMP_STALE_MS (the source being configured is the caller's part).
inline bool batteryTemp(const Reading& r, TimeNs now) noexcept {
  return within(r, now, fromMs(k::BATTERY_TEMP_STALE_MS)) && r.value >= k::BATTERY_TEMP_VALID_MIN_C &&
         r.value <= k::BATTERY_TEMP_VALID_MAX_C;
}

// The engine's own speed (NMEA 2000 PGN 127488 arrives every 0.1 s): a speed
// older than a second is a silent ECU, read as no speed.
inline constexpr double kEngineRpmMaxAgeS = 1.0;
inline bool engineRpm(const Reading& r, TimeNs now) noexcept {
  return within(r, now, fromSec(kEngineRpmMaxAgeS));
}

// What a BMS reports (limits and its SoC): stale after BmsStaleS, the
// parameter the owner sets for the BMS limits. heardAt: when it last spoke
// (a caller still waiting for the first report passes when it began to wait).
inline bool bms(TimeNs heardAt, TimeNs now, double bmsStaleS) noexcept {
  return now - heardAt <= fromSec(bmsStaleS);
}

// The engine turns: the alternator (or the engine) reads at least this
// speed. Below it the wear count, the charge-hold check and the health
// estimators treat the engine as stopped.
inline constexpr double kEngineTurningRpm = 200.0;
inline bool engineTurning(double rpm) noexcept { return finite(rpm) && rpm >= kEngineTurningRpm; }

}  // namespace xr::fresh
