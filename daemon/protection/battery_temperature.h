#pragma once
// BatteryTemperatureGuard (docs/batteries.md "Temperature rules"):
// what the battery temperature allows this tick.
//
//   - below ChargeMinTempC: REASON_BATTERY_COLD, no charging; released
//     BATTERY_COLD_HYSTERESIS_C above it;
//   - from ChargeMinTempC to ChargeFullCurrentTempC: a current cap that ramps
//     from 0 to MaximumAllowedBatteryAmps;
//   - above ChargeMaxTempC: REASON_BATTERY_HOT, no charging; released
//     BATTERY_HOT_HYSTERESIS_C below it;
//   - no fresh temperature: with BatteryTempRequired the current is capped at
//     C/10 (at 0 until a configured source posts its first sample); without
//     it the bank charges uncompensated. One warning event per episode.
//
// Pure: the temperature arrives in Inputs with its stamp and source; events
// go into the tick's batch. Trips and clears are events, never the buzzer,
// and the hystereses keep a temperature at a limit from chattering.
#include <cstdint>
#include <string_view>

#include "core/events.h"
#include "core/inputs.h"
#include "params/params.h"

namespace xr {

// Why the rules cap the charge current (the owner model's words: docs/dashboard.md "Owner model").
enum class BatteryTempCap : std::uint8_t {
  NONE,
  NO_PROBE,       // BatteryTempRequired and no fresh temperature: C/10
  WAITING_PROBE,  // a configured sensor has not sent its first sample: 0 A
  COLD_RAMP,      // between ChargeMinTempC and ChargeFullCurrentTempC
};
std::string_view toString(BatteryTempCap c);

struct BatteryTempDecision {
  bool known = false;          // a valid sample no older than BATTERY_TEMP_STALE_MS
  double tempC = kNoValue;     // that sample (NaN when not known)
  bool cold = false;           // REASON_BATTERY_COLD acting
  bool hot = false;            // REASON_BATTERY_HOT acting
  double currentCapA = 1e300;  // on the current command (1e300 = none)
  BatteryTempCap capCause = BatteryTempCap::NONE;
};

class BatteryTemperatureGuard {
 public:
  const BatteryTempDecision& update(const Inputs& in, const Params& p, EventBatch& ev) noexcept;
  const BatteryTempDecision& decision() const noexcept { return d_; }

 private:
  BatteryTempDecision d_;
  TimeNs firstTick_ = -1;
  bool everKnown_ = false;
  bool missingReported_ = false;
};

}  // namespace xr
