#include "app/driver_sensors.h"

#include "drivers/ads1115/ads1115_inputs.h"
#include "drivers/ina228/ina228_inputs.h"

namespace xr::app {

DriverSensors::StartReport DriverSensors::start(TimeNs now, double bovlVolts) {
  StartReport r;
  r.inaError = ina_.start(now);
  if (bovlVolts > 0.0) {
    ina_.setBusOvervoltageLimit(bovlVolts);
    bovl_ = bovlVolts;
  }
  ina_.setFastMode(false);  // field is off at start
  r.adsError = ads_.start(now);
  return r;
}

bool DriverSensors::read(TimeNs now, Inputs& in) noexcept {
  ina_.poll(now);
  fillInaInputs(ina_, in);
  fillAdsInputs(ads_.poll(now), in);
  const bool ok = ina_.stats().failedReads == lastInaFailures_ && ads_.stats().failedReads == lastAdsFailures_;
  lastInaFailures_ = ina_.stats().failedReads;
  lastAdsFailures_ = ads_.stats().failedReads;
  return ok;
}

void DriverSensors::apply(const Outputs& out) noexcept {
  if (out.inaFastMode != ina_.fastModeActive()) ina_.setFastMode(out.inaFastMode);
  // BOVL follows VoltageHardwareLimit (BulkVoltage + 0.3 V) on every change.
  if (out.inaBovlVolts > 0.0 && out.inaBovlVolts != bovl_) {
    if (ina_.setBusOvervoltageLimit(out.inaBovlVolts) == 0) bovl_ = out.inaBovlVolts;
  }
}

}  // namespace xr::app
