#pragma once
// FastSensors on the real INA228 and ADS1115 drivers: the same code on the
// board (i2c-dev) and in simulation (the simulated I2C bus). Maps driver
// samples into core/inputs.h with their stamps and freshness, and applies
// the regulator's INA requests (fast mode while the field is on, BOVL =
// VoltageHardwareLimit, reprogrammed whenever it changes).
#include "drivers/ads1115/ads1115_driver.h"
#include "drivers/ina228/ina228_driver.h"
#include "runtime/cycle_devices.h"

namespace xr::app {

class DriverSensors final : public rt::FastSensors {
 public:
  DriverSensors(Ina228Driver& ina, Ads1115Driver& ads) : ina_(ina), ads_(ads) {}
  // Not RT: detect + configure both chips. Failures are not fatal (the
  // drivers re-detect; the core sees the readings stale and keeps the field
  // off), but are reported.
  struct StartReport {
    int inaError = 0;
    int adsError = 0;
  };
  StartReport start(TimeNs now, double bovlVolts);

  bool read(TimeNs now, Inputs& in) noexcept override;
  void apply(const Outputs& out) noexcept override;

 private:
  Ina228Driver& ina_;
  Ads1115Driver& ads_;
  double bovl_ = 0.0;
  unsigned long lastInaFailures_ = 0, lastAdsFailures_ = 0;
};

}  // namespace xr::app
