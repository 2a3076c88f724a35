#pragma once
// The fast sensors of one control tick through the REAL drivers: INA228 and
// ADS1115 behind any I2cBus (i2c-dev on the board, SimI2cBus here). Fills
// only its own fields of Inputs and passes the regulator's INA requests
// (fast mode, BOVL) back to the driver. Nothing simulation-specific: the
// daemon may use it on the board too.
#include "config/settings.h"
#include "drivers/ads1115/ads1115_driver.h"
#include "drivers/ina228/ina228_driver.h"
#include "runtime/cycle_devices.h"

namespace xr::sim {

class DriverFastSensors final : public rt::FastSensors {
 public:
  DriverFastSensors(I2cBus& bus, const HardwareSettings& hw, const Clock& clock);
  // Detect + configure both chips (a missing chip is retried by its driver).
  void start(TimeNs now) noexcept;
  bool read(TimeNs now, Inputs& in) noexcept override;
  void apply(const Outputs& out) noexcept override;
  Ina228Driver& ina() noexcept { return ina_; }
  Ads1115Driver& ads() noexcept { return ads_; }

 private:
  Ina228Driver ina_;
  Ads1115Driver ads_;
};

}  // namespace xr::sim
