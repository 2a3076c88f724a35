// ShuntGainCorrector (docs/batteries.md "Auto shunt-gain correction").
#include "battery/shunt_gain.h"

#include <algorithm>
#include <cmath>

#include "battery/monitor_helpers.h"

namespace xr {

using namespace battery_detail;

void ShuntGainCorrector::atFullCharge(const GainCorrectionInput& in, EventBatch& ev) noexcept {
  using namespace battery_k;
  if (!in.enabled) {
    lastGuard_ = GainGuard::FeatureOff;
    return;
  }
  if (haveCorrection_ && in.now - lastCorrection_ < fromMs(MIN_GAIN_CORRECTION_INTERVAL_MS)) {
    lastGuard_ = GainGuard::TooSoon;
    return;
  }
  if (!in.referenceValid) {
    lastGuard_ = GainGuard::NoReference;
    return;
  }
  const double calculatedCapacity = in.countSinceReference_Ah;
  const double expectedCapacity = in.expectedCapacity_Ah;
  if (!finite(calculatedCapacity) || calculatedCapacity < MIN_PLAUSIBLE_CAPACITY_AH ||
      expectedCapacity < MIN_PLAUSIBLE_CAPACITY_AH) {
    lastGuard_ = GainGuard::ImplausibleCapacity;
    return;
  }
  const double errorRatio = std::fabs(expectedCapacity - calculatedCapacity) / expectedCapacity;
  if (errorRatio > MAX_REASONABLE_ERROR) {
    lastGuard_ = GainGuard::ErrorTooLarge;
    ev.push(makeEvent(in.now, EventLevel::Warning, EventCode::ShuntGainCorrected, factor_, errorRatio,
                      static_cast<int>(GainGuard::ErrorTooLarge)));
    return;
  }
  const double currentFactor = factor_;
  const double desiredCorrectionFactor = expectedCapacity / calculatedCapacity;
  double newFactor = currentFactor * desiredCorrectionFactor;
  const double maxChange = currentFactor * MAX_GAIN_ADJUSTMENT_PER_CYCLE;
  newFactor = std::clamp(newFactor, currentFactor - maxChange, currentFactor + maxChange);
  newFactor = std::clamp(newFactor, MIN_DYNAMIC_GAIN_FACTOR, MAX_DYNAMIC_GAIN_FACTOR);
  factor_ = newFactor;
  haveCorrection_ = true;
  lastCorrection_ = in.now;
  lastGuard_ = GainGuard::Applied;
  ev.push(makeEvent(in.now, EventLevel::Info, EventCode::ShuntGainCorrected, newFactor, currentFactor, 0));
}

void ShuntGainCorrector::restore(double factor) noexcept {
  factor_ = clampFinite(factor, battery_k::MIN_DYNAMIC_GAIN_FACTOR, battery_k::MAX_DYNAMIC_GAIN_FACTOR, 1.0);
}

}  // namespace xr
