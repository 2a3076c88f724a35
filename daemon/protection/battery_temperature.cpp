#include "protection/battery_temperature.h"

#include <algorithm>
#include <cmath>

#include "core/freshness.h"
#include "params/constants.h"

namespace xr {

namespace {

bool sampleKnown(const Inputs& in) {
  const Reading& r = in.batteryTempC;
  return in.batteryTempSource != BatteryTempSource::none && fresh::batteryTemp(r, in.now);
}

}  // namespace

std::string_view toString(BatteryTempCap c) {
  switch (c) {
    case BatteryTempCap::NONE:
      return "NONE";
    case BatteryTempCap::NO_PROBE:
      return "NO_PROBE";
    case BatteryTempCap::WAITING_PROBE:
      return "WAITING_PROBE";
    case BatteryTempCap::COLD_RAMP:
      return "COLD_RAMP";
  }
  return "NONE";
}

const BatteryTempDecision& BatteryTemperatureGuard::update(const Inputs& in, const Params& p,
                                                           EventBatch& ev) noexcept {
  if (firstTick_ < 0) firstTick_ = in.now;
  const bool known = sampleKnown(in);
  const double t = known ? in.batteryTempC.value : kNoValue;
  d_.known = known;
  d_.tempC = t;
  d_.currentCapA = 1e300;
  d_.capCause = BatteryTempCap::NONE;

  if (known) {
    everKnown_ = true;
    if (missingReported_) {
      missingReported_ = false;
      ev.push(makeEvent(in.now, EventLevel::Info, EventCode::BatteryTempBack, Reason::NONE, t));
    }
    // Cold lockout with its release hysteresis.
    if (!d_.cold && t < p.ChargeMinTempC) {
      d_.cold = true;
      ev.push(makeEvent(in.now, EventLevel::Warning, EventCode::ProtectionTrip, Reason::REASON_BATTERY_COLD,
                        t, p.ChargeMinTempC));
    } else if (d_.cold && t >= p.ChargeMinTempC + k::BATTERY_COLD_HYSTERESIS_C) {
      d_.cold = false;
      ev.push(makeEvent(in.now, EventLevel::Info, EventCode::ProtectionClear, Reason::REASON_BATTERY_COLD, t,
                        p.ChargeMinTempC));
    }
    // Hot stop, resuming 3 degC below the limit.
    if (!d_.hot && t > p.ChargeMaxTempC) {
      d_.hot = true;
      ev.push(makeEvent(in.now, EventLevel::Warning, EventCode::ProtectionTrip, Reason::REASON_BATTERY_HOT, t,
                        p.ChargeMaxTempC));
    } else if (d_.hot && t <= p.ChargeMaxTempC - k::BATTERY_HOT_HYSTERESIS_C) {
      d_.hot = false;
      ev.push(makeEvent(in.now, EventLevel::Info, EventCode::ProtectionClear, Reason::REASON_BATTERY_HOT, t,
                        p.ChargeMaxTempC));
    }
    // Reduced current just above the cold limit: 0 at ChargeMinTempC, full
    // (MaximumAllowedBatteryAmps) at ChargeFullCurrentTempC.
    const double span = p.ChargeFullCurrentTempC - p.ChargeMinTempC;
    if (span > 0.0 && t < p.ChargeFullCurrentTempC) {
      d_.currentCapA = std::clamp((t - p.ChargeMinTempC) / span, 0.0, 1.0) * p.MaximumAllowedBatteryAmps;
      d_.capCause = BatteryTempCap::COLD_RAMP;
    }
    return d_;
  }

  // No temperature: nothing can be said about cold or hot any more.
  if (d_.cold)
    ev.push(makeEvent(in.now, EventLevel::Info, EventCode::ProtectionClear, Reason::REASON_BATTERY_COLD));
  if (d_.hot)
    ev.push(makeEvent(in.now, EventLevel::Info, EventCode::ProtectionClear, Reason::REASON_BATTERY_HOT));
  d_.cold = d_.hot = false;
  const bool sourceConfigured = in.batteryTempSource != BatteryTempSource::none;
  const bool waitingFirst =
      sourceConfigured && !everKnown_ && in.now - firstTick_ < fromMs(k::BATTERY_TEMP_FIRST_SAMPLE_MS);
  if (p.BatteryTempRequired) {
    d_.currentCapA = waitingFirst ? 0.0 : k::BATTERY_NO_TEMP_RATE_C * p.BatteryCapacity_Ah;
    d_.capCause = waitingFirst ? BatteryTempCap::WAITING_PROBE : BatteryTempCap::NO_PROBE;
  }
  // Only worth a warning when something depends on the temperature.
  const bool matters = sourceConfigured || p.BatteryTempRequired || p.TempCompMvPerCellC != 0.0;
  if (matters && !waitingFirst && !missingReported_) {
    missingReported_ = true;
    ev.push(makeEvent(in.now, EventLevel::Warning, EventCode::BatteryTempMissing, Reason::NONE,
                      p.BatteryTempRequired ? d_.currentCapA : 0.0, 0.0, p.BatteryTempRequired ? 1 : 0));
  }
  return d_;
}

}  // namespace xr
