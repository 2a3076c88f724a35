#pragma once
// FastSensors on the REAL INA228 and ADS1115 drivers, behind any I2cBus:
// i2c-dev on the board, the simulated bus in simulation (the daemon's
// --sim rig and the headless SimRunner use this same class). Maps driver
// samples into core/inputs.h with their stamps and freshness, and applies
// the regulator's INA requests (fast mode while the field is on, BOVL =
// VoltageHardwareLimit, reprogrammed whenever it changes).
//
// ADS1115 pacing (docs/architecture.md): with ALERT/RDY wired (`readyEdges`), the loop
// hands every conversion-ready edge to onReadyEdge() and every conversion is
// used (~860 samples/s, CH1 ~430/s with the default sequence). If no edge
// has arrived for kEdgeSilence while the chip answers, the chip is restarted
// in ready mode once (a power glitch resets it to single-shot with the
// comparator off); if it stays silent for another kEdgeSilence (line not
// wired, wrong line number, broken wire), the driver falls back to
// single-shot pacing (one conversion per tick) and edgeFallback() says so:
// the regulator keeps its sensors and the supervisor logs what to fix.
#include <array>
#include <cstdint>

#include "config/settings.h"
#include "drivers/ads1115/ads1115_driver.h"
#include "drivers/ina228/ina228_driver.h"
#include "runtime/cycle_devices.h"

namespace xr {

class DriverSensors final : public rt::FastSensors {
 public:
  static constexpr TimeNs kEdgeSilence = 250'000'000;  // ~200 missed edges

  DriverSensors(I2cBus& bus, const HardwareSettings& hw, const Clock& clock, bool readyEdges);

  // Not RT: detect + configure both chips. Failures are not fatal (the
  // drivers re-detect; the core sees the readings stale and keeps the field
  // off), but are reported (errno values, 0 = fine).
  struct StartReport {
    int inaError = 0;
    int adsError = 0;
  };
  StartReport start(TimeNs now, double bovlVolts) noexcept;

  bool read(TimeNs now, Inputs& in) noexcept override;
  void apply(const Outputs& out) noexcept override;
  void onReadyEdge(TimeNs edge) noexcept override;

  // True once ready-edge pacing was abandoned for lack of edges.
  bool edgeFallback() const noexcept { return sampleCounts_.readyEdgeFallback; }
  Ina228Driver& ina() noexcept { return ina_; }
  Ads1115Driver& ads() noexcept { return ads_; }

 private:
  Ina228Driver ina_;
  Ads1115Driver ads_;
  // Per-channel result counts as of the last read() and the fallback flag
  // (edgeFallback()): what FastSensors::sampleCounts() points at.
  rt::SampleCounts sampleCounts_{};
  double bovl_ = 0.0;
  TimeNs lastEdge_ = 0;            // last edge, or when edge pacing (re)started
  bool silenceRestarted_ = false;  // one restart in ready mode already tried
  unsigned long lastInaFailures_ = 0, lastAdsFailures_ = 0;
};

}  // namespace xr
