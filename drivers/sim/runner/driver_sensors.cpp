#include "drivers/sim/runner/driver_sensors.h"

#include "drivers/ads1115/ads1115_inputs.h"
#include "drivers/ina228/ina228_inputs.h"

namespace xr::sim {

DriverFastSensors::DriverFastSensors(I2cBus& bus, const HardwareSettings& hw, const Clock& clock)
    : ina_(bus, hw.ina228_address, hw.shunt_resistance_ohm, hw.shunt_max_current_a),
      ads_(bus, hw.ads1115_address, hw.ads_channel_sequence, hw.frontend, clock, AdsPacing::SingleShot) {}

void DriverFastSensors::start(TimeNs now) noexcept {
  ina_.start(now);
  ads_.start(now);
}

bool DriverFastSensors::read(TimeNs now, Inputs& in) noexcept {
  const auto inaFailed = ina_.stats().failedReads;
  const auto adsFailed = ads_.stats().failedReads;

  ina_.poll(now);
  fillInaInputs(ina_, in);
  fillAdsInputs(ads_.poll(now), in);
  return ina_.stats().failedReads == inaFailed && ads_.stats().failedReads == adsFailed;
}

void DriverFastSensors::apply(const Outputs& out) noexcept {
  if (ina_.present()) {
    if (out.inaFastMode != ina_.fastModeActive()) ina_.setFastMode(out.inaFastMode);
    if (out.inaBovlVolts > 0.0 && out.inaBovlVolts != ina_.busOvervoltageLimit())
      ina_.setBusOvervoltageLimit(out.inaBovlVolts);
  }
}

}  // namespace xr::sim
