// AltCurrentAutoZero (docs/batteries.md "Auto-zero").
#include "battery/battery_auto_zero.h"

#include <cmath>

#include "battery/monitor_helpers.h"
#include "params/constants.h"

namespace xr {

using namespace battery_detail;

bool AltCurrentAutoZero::checkTriggers(const AutoZeroInput& in, EventBatch& ev) noexcept {
  const double temp = in.tempF;
  if (!haveTemp_ && finite(temp)) {
    haveTemp_ = true;
    lastTemp_ = temp;
  }
  if (!in.enabled || active_) return false;
  const double rpm = in.rpm;
  if (!finite(rpm) || rpm < k::AUTO_ZERO_MIN_RPM) return false;
  const bool intervalDue = in.now - lastRun_ >= fromMs(k::AUTO_ZERO_INTERVAL);
  const bool tempShift = haveTemp_ && finite(temp) && std::fabs(temp - lastTemp_) >= k::AUTO_ZERO_TEMP_DELTA;
  if (!intervalDue && !tempShift) return false;
  active_ = true;
  start_ = in.now;
  sum_ = 0.0;
  count_ = 0;
  ev.push(makeEvent(in.now, EventLevel::Info, EventCode::AutoZeroStarted, zero_, 0.0, tempShift ? 1 : 0));
  return true;
}

bool AltCurrentAutoZero::sample(const AutoZeroInput& in, EventBatch& ev) noexcept {
  const TimeNs elapsed = in.now - start_;
  if (elapsed < fromMs(battery_k::AUTO_ZERO_DURATION_MS)) {
    // Field is held off by the caller; sample only after the 2 s settle and
    // only new CH1 conversions (the same sample must not count twice).
    if (elapsed > fromMs(k::AUTO_ZERO_SETTLE_MS) && in.altCurrentRaw.fresh &&
        finite(in.altCurrentRaw.value)) {
      sum_ += in.altCurrentRaw.value;
      ++count_;
    }
    return true;
  }
  int detail = 0;
  double zero = zero_;
  if (count_ == 0) {
    detail = 1;  // no samples: keep the old zero
  } else {
    const double mean = sum_ / static_cast<double>(count_);
    if (std::fabs(mean) > battery_k::AUTO_ZERO_MAX_OFFSET_A)
      detail = 2;
    else
      zero = mean;
  }
  zero_ = zero;
  lastRun_ = in.now;
  if (finite(in.tempF)) {
    lastTemp_ = in.tempF;
    haveTemp_ = true;
  }
  active_ = false;
  start_ = 0;
  ev.push(makeEvent(in.now, detail == 0 ? EventLevel::Info : EventLevel::Warning, EventCode::AutoZeroDone,
                    zero, static_cast<double>(count_), detail));
  return false;
}

void AltCurrentAutoZero::restore(double zero) noexcept {
  zero_ = clampFinite(zero, -battery_k::AUTO_ZERO_MAX_OFFSET_A, battery_k::AUTO_ZERO_MAX_OFFSET_A, 0.0);
}

}  // namespace xr
