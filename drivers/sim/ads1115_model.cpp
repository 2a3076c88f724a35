#include "drivers/sim/ads1115_model.h"

#include <algorithm>
#include <cerrno>
#include <cmath>

namespace xr::sim {
using namespace ads1115;

namespace {
constexpr std::uint16_t OS = 0x8000;
constexpr std::uint16_t MODE_SINGLE = 0x0100;
int muxOf(std::uint16_t c) { return (c >> 12) & 7; }
int pgaOf(std::uint16_t c) { return (c >> 9) & 7; }
int drOf(std::uint16_t c) { return (c >> 5) & 7; }
int queOf(std::uint16_t c) { return c & 3; }
}  // namespace

Ads1115Model::Ads1115Model(double clockScale) : clockScale_(clockScale > 0.0 ? clockScale : 1.0) {
  for (int dr = 0; dr < 8; ++dr) period_[dr] = static_cast<TimeNs>(1e9 / kDataRateSps[dr] * clockScale_);
}

std::uint16_t Ads1115Model::peekConfig() const noexcept {
  // OS reads 0 while a conversion is running, 1 when idle.
  return static_cast<std::uint16_t>((config_ & ~OS) | (converting_ ? 0 : OS));
}

std::int16_t Ads1115Model::sample(std::uint16_t cfg) noexcept {
  // MUX -> AINp, AINn (-1 = GND), as tables instead of a switch. The
  // positive input is sampled (and draws its noise) before the negative one.
  static constexpr std::int8_t kPos[8] = {0, 0, 1, 2, 0, 1, 2, 3};
  static constexpr std::int8_t kNeg[8] = {1, 3, 3, 3, -1, -1, -1, -1};
  const int mux = muxOf(cfg);
  double v = pin(kPos[mux]);
  if (kNeg[mux] >= 0) v -= pin(kNeg[mux]);
  const double fs = kFsrVolts[pgaOf(cfg)];
  const double code = std::nearbyint(v / fs * 32768.0);
  if (!(code == code)) return 0;
  return static_cast<std::int16_t>(std::clamp(code, -32768.0, 32767.0));  // clips at ±FS
}

void Ads1115Model::startConversion(TimeNs at) noexcept {
  converting_ = true;
  convConfig_ = config_;  // settings in force for this conversion
  convEnd_ = at + period(drOf(config_));
  // Single-shot with the RDY function: the pin follows OS (busy = inactive).
  if (readyMode() && queOf(config_) != 3 && (config_ & MODE_SINGLE)) alert_ = false;
}

void Ads1115Model::finishConversion() noexcept {
  conversion_ = sample(convConfig_);
  ++conversions_;
  if (pulses_) {
    // Continuous conversion-ready mode (the driver's): a ready pulse and the
    // next conversion at once, what the general path below does in this
    // mode, without re-deciding the mode from config_ per conversion.
    ++readyPulses_;
    alert_ = false;
    convConfig_ = config_;
    convEnd_ += period(drOf(config_));
    return;
  }
  converting_ = false;
  const std::uint16_t cfg = config_;
  if (queOf(cfg) != 3) {
    if (readyMode()) {
      // Conversion-ready: single-shot asserts until the next start; continuous
      // gives a short pulse per conversion (counted; the pin idles between).
      ++readyPulses_;
      alert_ = (cfg & MODE_SINGLE) != 0;
    } else {
      const std::int16_t hi = std::int16_t(hiThresh_), lo = std::int16_t(loThresh_);
      const bool window = cfg & 0x0010;
      const bool beyond = conversion_ > hi || (window && conversion_ < lo);
      const int need = 1 << queOf(cfg);  // 1, 2 or 4 conversions
      queueCount_ = beyond ? queueCount_ + 1 : 0;
      if (queueCount_ >= need) alert_ = true;
      const bool latch = cfg & 0x0004;
      if (!latch && alert_) {
        // Traditional: releases below Lo_thresh; window: back inside.
        const bool release = window ? (conversion_ <= hi && conversion_ >= lo) : conversion_ < lo;
        if (release) alert_ = false;
      }
    }
  } else {
    alert_ = false;  // comparator disabled: pin high-impedance
  }
  // Continuous mode converts back to back with the settings now in force
  // (a config change applied after the conversion in progress).
  if (!(config_ & MODE_SINGLE)) startConversion(convEnd_);
}

void Ads1115Model::convertTo(TimeNs t) noexcept {
  while (converting_ && convEnd_ <= t) {
    now_ = convEnd_;
    finishConversion();
  }
  now_ = t;
}

int Ads1115Model::read(std::uint8_t* buf, std::size_t len) noexcept {
  if (len == 0 || len > 2) {
    ++protocolErrors_;
    return EREMOTEIO;
  }
  std::uint16_t v = 0;
  switch (ptr_) {
    case 0:
      v = readConversion();
      break;
    case 1:
      v = peekConfig();
      break;
    case 2:
      v = loThresh_;
      break;
    default:
      v = hiThresh_;
      break;
  }
  buf[0] = std::uint8_t(v >> 8);
  if (len == 2) buf[1] = std::uint8_t(v);
  return 0;
}

int Ads1115Model::write(const std::uint8_t* buf, std::size_t len) noexcept {
  if (len == 0 || (buf[0] & 0xFC) != 0) {  // pointer bits 7:2 must be 0
    ++protocolErrors_;
    return EREMOTEIO;
  }
  const std::uint8_t reg = buf[0] & 3;
  if (len == 1) {
    ptr_ = reg;
    return 0;
  }
  if (len != 3 || reg == 0) {  // Conversion register is read-only
    ++protocolErrors_;
    return EREMOTEIO;
  }
  ptr_ = reg;
  const std::uint16_t v = static_cast<std::uint16_t>((buf[1] << 8) | buf[2]);
  if (reg >= 2) {
    (reg == 2 ? loThresh_ : hiThresh_) = v;
    ready_ = (hiThresh_ & 0x8000) && !(loThresh_ & 0x8000);
    pulses_ = readyMode() && queOf(config_) != 3 && !(config_ & MODE_SINGLE);
  } else {
    writeConfig(v);
  }
  return 0;
}

std::uint16_t Ads1115Model::readConversion() noexcept {
  // A latched comparator alert clears when the Conversion register is read.
  if ((config_ & 0x0004) && !readyMode()) alert_ = false;
  return static_cast<std::uint16_t>(conversion_);
}

void Ads1115Model::writeConfig(std::uint16_t v) noexcept {
  config_ = static_cast<std::uint16_t>(v & ~OS);
  queueCount_ = 0;
  if (queOf(config_) == 3) alert_ = false;
  if (!(config_ & MODE_SINGLE)) {
    // Continuous: start now if powered down; otherwise the running
    // conversion finishes with its old settings and the next one uses these.
    if (!converting_) startConversion(now_);
  } else if ((v & OS) && !converting_) {
    startConversion(now_);  // single-shot start; ignored while busy
  }
  pulses_ = readyMode() && queOf(config_) != 3 && !(config_ & MODE_SINGLE);
}

}  // namespace xr::sim
