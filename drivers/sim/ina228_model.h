#pragma once
// TI INA228 register-level model, written from docs/sources.md D1 (the TI
// datasheet SLYS021A), not from our driver, so the two check each other.
//
// What it models: the register map with reset values and access rights,
// big-endian 16/24/40-bit registers, CONFIG (RST, RSTACC, CONVDLY, ADCRANGE)
// and ADC_CONFIG (MODE, VBUSCT/VSHCT/VTCT, AVG) setting the update cadence
// (sum of active conversion times x averages), SHUNT_CAL arithmetic for
// CURRENT/POWER/ENERGY/CHARGE, 20-bit VSHUNT/VBUS/CURRENT, 16-bit DIETEMP,
// the six limit comparisons with DIAG_ALRT flags, ALATCH latching, SLOWALERT
// (raw vs averaged comparison) and the ALERT pin (open drain, APOL).
// Refused (NACK + protocolErrors): a bad pointer, a write to a read-only or
// reserved register, a write of the wrong length, a read longer than the
// register.
#include <algorithm>
#include <cstdint>
#include <limits>

#include "drivers/sim/sim_i2c_device.h"

namespace xr::sim {

namespace ina228 {
enum Reg : std::uint8_t {
  CONFIG = 0x00,
  ADC_CONFIG = 0x01,
  SHUNT_CAL = 0x02,
  SHUNT_TEMPCO = 0x03,
  VSHUNT = 0x04,
  VBUS = 0x05,
  DIETEMP = 0x06,
  CURRENT = 0x07,
  POWER = 0x08,
  ENERGY = 0x09,
  CHARGE = 0x0A,
  DIAG_ALRT = 0x0B,
  SOVL = 0x0C,
  SUVL = 0x0D,
  BOVL = 0x0E,
  BUVL = 0x0F,
  TEMP_LIMIT = 0x10,
  PWR_LIMIT = 0x11,
  MANUFACTURER_ID = 0x3E,
  DEVICE_ID = 0x3F,
};
// DIAG_ALRT bits
inline constexpr std::uint16_t ALATCH = 1u << 15, CNVR = 1u << 14, SLOWALERT = 1u << 13, APOL = 1u << 12,
                               ENERGYOF = 1u << 11, CHARGEOF = 1u << 10, MATHOF = 1u << 9, TMPOL = 1u << 7,
                               SHNTOL = 1u << 6, SHNTUL = 1u << 5, BUSOL = 1u << 4, BUSUL = 1u << 3,
                               POL = 1u << 2, CNVRF = 1u << 1, MEMSTAT = 1u << 0;
inline constexpr std::uint16_t kLimitFlags = TMPOL | SHNTOL | SHNTUL | BUSOL | BUSUL | POL;
// Conversion time per VBUSCT/VSHCT/VTCT code, µs (docs/sources.md D1.3; code 7 = 4120).
inline constexpr int kConvTimeUs[8] = {50, 84, 150, 280, 540, 1052, 2074, 4120};
inline constexpr int kAvgSamples[8] = {1, 4, 16, 64, 128, 256, 512, 1024};
// Register size in bytes (0 = reserved address).
int regSize(std::uint8_t reg) noexcept;
}  // namespace ina228

// What the chip's pins see, set by the plant before update().
struct Ina228Analog {
  double vshunt_v = 0.0;  // IN+ - IN-
  double vbus_v = 0.0;    // VBUS pin to GND
  double dietemp_c = 25.0;
};

class Ina228Model final : public SimI2cDevice {
 public:
  Ina228Model();

  // The raw codes are quantised here, once per input change (a register
  // write that changes the quantisation redoes them at the next sample).
  void setAnalog(const Ina228Analog& a) noexcept {
    analog_ = a;
    quantise();
  }
  void update(TimeNs t) noexcept override {
    if (t <= now_) return;
    if (running_ && nextSample_ <= t)
      convertTo(t);
    else
      now_ = t;
  }
  int write(const std::uint8_t* buf, std::size_t len) noexcept override;
  int read(std::uint8_t* buf, std::size_t len) noexcept override;

  // Logical ALERT: true while the pin is driven active (pulled low with
  // APOL=0). The board wiring ANDs it into the gate-driver enable.
  bool alertActive() const noexcept {
    if (diag_ & ina228::kLimitFlags) return true;
    return (diag_ & ina228::CNVR) && (diag_ & ina228::CNVRF);
  }
  // Electrical pin level: open drain with a pull-up (true = high).
  bool alertPinHigh() const noexcept { return (diag_ & ina228::APOL) ? alertActive() : !alertActive(); }

  // Raw register value (for tests), without read side effects.
  std::uint64_t peek(std::uint8_t reg) const noexcept;
  // Time between two result updates under the current ADC_CONFIG (0 in shutdown).
  TimeNs updatePeriod() const noexcept;
  std::uint64_t conversions() const noexcept { return conversions_; }

 private:
  void convertTo(TimeNs t) noexcept;  // update() with at least one raw sample due by t
  void quantise() noexcept;           // the raw codes of analog_ (codesValid_)
  void reset() noexcept;
  void restartConversions() noexcept;
  void onSample() noexcept;                 // one raw sample of every active channel
  void publish(double dtSeconds) noexcept;  // the averaged result is ready
  void refreshLimits() noexcept;            // after any register write or reset
  // A 20-bit result (VSHUNT, VBUS, CURRENT) as its 24-bit register: the code
  // in bits 23..4.
  static std::uint32_t reg20(std::int32_t code) noexcept { return (std::uint32_t(code) & 0xFFFFF) << 4; }
  // The side effect of reading DIAG_ALRT: latched limit flags (ALATCH = 1)
  // and CNVRF clear.
  void clearOnDiagRead() noexcept {
    if (diag_ & ina228::ALATCH) diag_ &= ~ina228::kLimitFlags;
    diag_ &= ~ina228::CNVRF;
  }
  void compareLimits(std::int32_t vshCode, std::int32_t vbusCode, std::int32_t tempCode,
                     std::uint32_t powerCode) noexcept;
  int mode() const noexcept { return (adcConfig_ >> 12) & 0xF; }
  bool busActive() const noexcept { return mode() & 0x1; }
  bool shuntActive() const noexcept { return mode() & 0x2; }
  bool tempActive() const noexcept { return mode() & 0x4; }
  bool continuous() const noexcept { return mode() & 0x8; }
  TimeNs sampleTime() const noexcept;  // one pass over the active channels

  Ina228Analog analog_;
  TimeNs now_ = 0;
  std::uint8_t ptr_ = 0;
  std::uint16_t config_ = 0, adcConfig_ = 0, shuntCal_ = 0, tempco_ = 0;
  std::int32_t vshunt_ = 0, vbus_ = 0, current_ = 0;  // 20-bit codes
  std::int16_t dietemp_ = 0;
  std::uint32_t power_ = 0;  // 24-bit
  double energyAcc_ = 0.0;   // ENERGY in its LSBs; the register is the integer part (40-bit)
  double chargeAcc_ =
      0.0;  // CHARGE in its LSBs; the register is the truncated value (40-bit two's complement)
  std::uint16_t diag_ = 0, sovl_ = 0, suvl_ = 0, bovl_ = 0, buvl_ = 0, tempLimit_ = 0, pwrLimit_ = 0;
  bool limitActive_ = false;  // some limit condition true at the last comparison
  // compareLimits() bounds of the measured channels (refreshLimits()).
  std::int32_t limTemp_ = 0, limSovl_ = 0, limSuvl_ = 0, limBovl_ = 0, limBuvl_ = 0;
  bool limPol_ = false;
  std::uint16_t measured_ = 0;
  // Conversion engine state.
  bool running_ = false;
  TimeNs nextSample_ = 0;
  TimeNs sampleTime_ = 1;   // sampleTime() while running (set when conversions restart)
  int avg_ = 1;             // samples per result (AVG) while running, set with sampleTime_
  double publishDt_ = 0.0;  // seconds per result (sampleTime_ x avg_), for ENERGY/CHARGE
  // Raw ADC codes of analog_ (constant until the next setAnalog() or an
  // ADCRANGE change): quantised once, not per raw sample batch.
  bool codesValid_ = false;
  std::int32_t vshCode_ = 0, vbusCode_ = 0, tcode_ = 0;
  std::uint32_t rawPower_ = 0;
  int samplesInWindow_ = 0;
  std::int64_t sumVsh_ = 0, sumVbus_ = 0, sumTemp_ = 0;  // raw codes of the window
  std::uint64_t conversions_ = 0;
};

}  // namespace xr::sim
