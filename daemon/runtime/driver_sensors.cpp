#include "runtime/driver_sensors.h"

#include "drivers/ads1115/ads1115_inputs.h"
#include "drivers/ina228/ina228_inputs.h"

namespace xr {

DriverSensors::DriverSensors(I2cBus& bus, const HardwareSettings& hw, const Clock& clock, bool readyEdges)
    : ina_(bus, hw.ina228_address, hw.shunt_resistance_ohm, hw.shunt_max_current_a),
      ads_(bus, hw.ads1115_address, hw.ads_channel_sequence, hw.frontend, clock,
           readyEdges ? AdsPacing::ReadyEdge : AdsPacing::SingleShot) {
  counts_ = &sampleCounts_;
}

DriverSensors::StartReport DriverSensors::start(TimeNs now, double bovlVolts) noexcept {
  StartReport r;
  r.inaError = ina_.start(now);
  if (bovlVolts > 0.0 && ina_.setBusOvervoltageLimit(bovlVolts) == 0) bovl_ = bovlVolts;
  ina_.setFastMode(false);  // the field is off at start
  r.adsError = ads_.start(now);
  lastEdge_ = now;
  return r;
}

bool DriverSensors::read(TimeNs now, Inputs& in) noexcept {
  if (ads_.pacing() == AdsPacing::ReadyEdge) {
    // A chip that does not answer explains the silence by itself (its own
    // re-detect runs); silence from an answering chip means no edges reach us.
    if (!ads_.present()) {
      lastEdge_ = now;
    } else if (now - lastEdge_ > kEdgeSilence) {
      if (!silenceRestarted_) {
        // First silence: the chip may have lost its configuration (a power
        // glitch leaves it single-shot with the comparator off, so it stops
        // pulsing). Restart it in ready mode once before giving up on edges.
        silenceRestarted_ = true;
        ads_.setPacing(AdsPacing::ReadyEdge, now);
        lastEdge_ = now;
      } else {
        sampleCounts_.readyEdgeFallback = true;
        ads_.setPacing(AdsPacing::SingleShot, now);
      }
    }
  }
  ina_.poll(now);
  fillInaInputs(ina_, in);
  const Ads1115Samples& ads = ads_.service(now);
  fillAdsInputs(ads, in);
  for (std::size_t i = 0; i < 4; ++i) sampleCounts_.ads[i] = ads.ch[i].count;
  ads_.clearFresh();
  const bool ok =
      ina_.stats().failedReads == lastInaFailures_ && ads_.stats().failedReads == lastAdsFailures_;
  lastInaFailures_ = ina_.stats().failedReads;
  lastAdsFailures_ = ads_.stats().failedReads;
  return ok;
}

void DriverSensors::onReadyEdge(TimeNs edge) noexcept {
  lastEdge_ = edge;
  silenceRestarted_ = false;
  ads_.onReadyEdge(edge);
}

void DriverSensors::apply(const Outputs& out) noexcept {
  if (!ina_.present()) return;
  if (out.inaFastMode != ina_.fastModeActive()) ina_.setFastMode(out.inaFastMode);
  // BOVL follows VoltageHardwareLimit (BulkVoltage + 0.3 V) on every change.
  if (out.inaBovlVolts > 0.0 && out.inaBovlVolts != bovl_) {
    if (ina_.setBusOvervoltageLimit(out.inaBovlVolts) == 0) bovl_ = out.inaBovlVolts;
  }
}

}  // namespace xr
