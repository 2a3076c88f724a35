#pragma once
// TI ADS1115 register-level model from docs/sources.md D2 (TI SBAS444):
// Config register (OS, MUX, PGA, MODE, DR, COMP_MODE/POL/LAT/QUE), one data
// period per conversion at the chosen data rate (scaled by the internal
// oscillator's tolerance, `clockScale`), single-shot and continuous modes,
// "a config change takes effect after the conversion in progress", results
// clipped at the ±FS codes 0x7FFF/0x8000, the digital comparator (traditional
// and window, queue, latch) and ALERT/RDY as a conversion-ready pin when
// Hi_thresh MSB = 1 and Lo_thresh MSB = 0.
// Refused (NACK + protocolErrors): pointer bits 7:2 set, a write to the
// Conversion register, a write of the wrong length, a read longer than 2.
#include <array>
#include <cstdint>
#include <limits>

#include "drivers/sim/prng.h"
#include "drivers/sim/sim_i2c_device.h"

namespace xr::sim {

namespace ads1115 {
inline constexpr int kDataRateSps[8] = {8, 16, 32, 64, 128, 250, 475, 860};
inline constexpr double kFsrVolts[8] = {6.144, 4.096, 2.048, 1.024, 0.512, 0.256, 0.256, 0.256};
}  // namespace ads1115

class Ads1115Model final : public SimI2cDevice {
 public:
  explicit Ads1115Model(double clockScale = 1.0);

  // Input pin voltages AIN0..AIN3 (to GND), set by the plant before update().
  void setInputs(const std::array<double, 4>& ain) noexcept { ain_ = ain; }
  void setInput(int ain, double v) noexcept { ain_[ain & 3] = v; }
  // Sensor noise drawn at the instant a conversion samples a pin: only the
  // pins the MUX of that conversion selects draw from `rng` (sigma[ain] volts,
  // none for a sigma of 0; see Rng::gauss), in the order AINp then AINn, and
  // the noisy voltage is clamped to [0, vmax] (the board's input protection;
  // a non-finite value reads as 0 V). nullptr: no noise, no clamp.
  void setInputNoise(Rng* rng, const std::array<double, 4>& sigma, double vmax) noexcept {
    rng_ = rng;
    sigma_ = sigma;
    vmax_ = vmax;
  }
  void setInputSigma(int ain, double sigma) noexcept { sigma_[ain & 3] = sigma; }
  void update(TimeNs t) noexcept override {
    if (t < now_) return;
    if (converting_ && convEnd_ <= t) {
      convertTo(t);
    } else {
      now_ = t;
    }
  }
  int write(const std::uint8_t* buf, std::size_t len) noexcept override;
  int read(std::uint8_t* buf, std::size_t len) noexcept override;

  // ALERT/RDY pin: true while driven active (low with COMP_POL = 0).
  bool alertActive() const noexcept { return alert_; }
  std::uint16_t peekConfig() const noexcept;
  std::int16_t peekConversion() const noexcept { return conversion_; }
  std::uint64_t conversions() const noexcept { return conversions_; }
  std::uint64_t readyPulses() const noexcept { return readyPulses_; }
  bool converting() const noexcept { return converting_; }
  // When the ALERT/RDY pin next pulses (end of the running conversion in
  // continuous conversion-ready mode), or -1 when it will not pulse on its
  // own. The simulated board's ALERT/RDY GPIO edges come from here.
  TimeNs nextReadyEdge() const noexcept { return converting_ && pulses_ ? convEnd_ : -1; }
  // Data period of a data-rate code under this chip's oscillator.
  TimeNs period(int dr) const noexcept { return period_[dr & 7]; }

 private:
  void convertTo(TimeNs t) noexcept;  // update() with a conversion ending by t
  void startConversion(TimeNs at) noexcept;
  std::uint16_t readConversion() noexcept;     // a read of the Conversion register, with its side effect
  void writeConfig(std::uint16_t v) noexcept;  // a write of the Config register
  void finishConversion() noexcept;
  // Hi_thresh MSB = 1 and Lo_thresh MSB = 0: ALERT/RDY is the conversion-ready
  // pin. Held as a flag, set when a threshold is written (asked per conversion
  // and per edge wait, written once per configuration).
  bool readyMode() const noexcept { return ready_; }
  std::int16_t sample(std::uint16_t cfg) noexcept;
  double pin(int ain) noexcept {
    if (!rng_) return ain_[ain];
    const double v = ain_[ain] + rng_->gauss(sigma_[ain]);
    if (v >= 0.0 && v <= vmax_) return v;  // the usual case: one range check
    // Above the clamp: vmax; below 0, NaN or infinite: 0 V.
    return (v > vmax_ && v < std::numeric_limits<double>::infinity()) ? vmax_ : 0.0;
  }

  std::array<double, 4> ain_{};
  Rng* rng_ = nullptr;
  std::array<double, 4> sigma_{};
  double vmax_ = 0.0;
  double clockScale_;
  std::array<TimeNs, 8> period_{};  // period(dr), computed once
  TimeNs now_ = 0;
  std::uint8_t ptr_ = 0;
  std::uint16_t config_ = 0x8583;  // reset value (OS bit read back as "idle")
  std::int16_t conversion_ = 0;
  std::uint16_t loThresh_ = 0x8000, hiThresh_ = 0x7FFF;
  bool ready_ = false;  // readyMode() of the reset thresholds
  // Continuous conversion-ready mode with the comparator on: the pin pulses
  // at each conversion end. Set with ready_ and config_ (a register write),
  // asked at every edge wait.
  bool pulses_ = false;
  bool converting_ = false;
  std::uint16_t convConfig_ = 0;  // settings latched when the conversion started
  TimeNs convEnd_ = 0;
  bool alert_ = false;
  int queueCount_ = 0;
  std::uint64_t conversions_ = 0, readyPulses_ = 0;
};

}  // namespace xr::sim
