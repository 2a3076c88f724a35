// BatteryMonitor: alternator current auto-zero (docs/batteries.md).
#include <algorithm>
#include <cmath>

#include "battery/battery_monitor.h"
#include "battery/monitor_helpers.h"
#include "core/alternator_temperature.h"
#include "params/constants.h"

namespace xr {

using namespace battery_detail;

// ---------------------------------------------------------------- auto-zero

double BatteryMonitor::temperatureF(const Inputs& in) const noexcept {
  return alternatorTemperature(in, p_.TempSource).value;
}

void BatteryMonitor::checkAutoZeroTriggers(const Inputs& in, EventBatch& ev) noexcept {
  const double temp = temperatureF(in);
  if (!started_) {
    started_ = true;
    lastTick_ = in.now;
    lastSocUpdate_ = in.now;
    lastChargeTimes_ = in.now;
    lastAutoZeroTime_ = in.now;  // hourly timer starts at the first tick
  }
  if (!haveAutoZeroTemp_ && finite(temp)) {
    haveAutoZeroTemp_ = true;
    lastAutoZeroTemp_ = temp;
  }
  if (!p_.AutoAltCurrentZero || autoZeroActive_) return;
  const double rpm = in.rpm.value;
  if (!finite(rpm) || rpm < k::AUTO_ZERO_MIN_RPM) return;
  const bool intervalDue = in.now - lastAutoZeroTime_ >= fromMs(k::AUTO_ZERO_INTERVAL);
  const bool tempShift =
      haveAutoZeroTemp_ && finite(temp) && std::fabs(temp - lastAutoZeroTemp_) >= k::AUTO_ZERO_TEMP_DELTA;
  if (!intervalDue && !tempShift) return;
  autoZeroActive_ = true;
  telemetryStale_ = true;
  autoZeroStartTime_ = in.now;
  autoZeroAccumulator_ = 0.0;
  autoZeroSampleCount_ = 0;
  ev.push(makeEvent(in.now, EventLevel::Info, EventCode::AutoZeroStarted, ledger_.DynamicAltCurrentZero, 0.0,
                    tempShift ? 1 : 0));
}

bool BatteryMonitor::processActiveAutoZero(const Inputs& in, EventBatch& ev) noexcept {
  const TimeNs elapsed = in.now - autoZeroStartTime_;
  if (elapsed < fromMs(battery_k::AUTO_ZERO_DURATION_MS)) {
    // Field is held off by the caller; sample only after the 2 s settle and
    // only new CH1 conversions (the same sample must not count twice).
    if (elapsed > fromMs(k::AUTO_ZERO_SETTLE_MS) && in.altCurrentRaw.fresh &&
        finite(in.altCurrentRaw.value)) {
      autoZeroAccumulator_ += in.altCurrentRaw.value;
      ++autoZeroSampleCount_;
    }
    return true;
  }
  int detail = 0;
  double zero = ledger_.DynamicAltCurrentZero;
  if (autoZeroSampleCount_ == 0) {
    detail = 1;  // no samples: keep the old zero
  } else {
    const double mean = autoZeroAccumulator_ / static_cast<double>(autoZeroSampleCount_);
    if (std::fabs(mean) > battery_k::AUTO_ZERO_MAX_OFFSET_A)
      detail = 2;
    else
      zero = mean;
  }
  ledger_.DynamicAltCurrentZero = zero;
  telemetryStale_ = true;
  lastAutoZeroTime_ = in.now;
  const double temp = temperatureF(in);
  if (finite(temp)) {
    lastAutoZeroTemp_ = temp;
    haveAutoZeroTemp_ = true;
  }
  autoZeroActive_ = false;
  autoZeroStartTime_ = 0;
  ev.push(makeEvent(in.now, detail == 0 ? EventLevel::Info : EventLevel::Warning, EventCode::AutoZeroDone,
                    zero, static_cast<double>(autoZeroSampleCount_), detail));
  return false;
}

}  // namespace xr
