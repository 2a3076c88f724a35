// TI INA228 model: the register map and the I2C messages (pointer writes,
// register reads with their side effects, register writes). The conversion
// engine (sampling, averaging, results, limit comparisons) is in
// ina228_model.cpp.
#include <array>
#include <cerrno>
#include <cstdint>

#include "drivers/sim/ina228_model.h"

namespace xr::sim {
namespace ina228 {
namespace {
// Register size in bytes by pointer value, 0 = reserved (read and write
// both look it up once per message: a table, not a switch).
constexpr std::array<std::uint8_t, 64> kRegSize = [] {
  std::array<std::uint8_t, 64> t{};
  for (std::uint8_t r : {CONFIG, ADC_CONFIG, SHUNT_CAL, SHUNT_TEMPCO, DIETEMP, DIAG_ALRT, SOVL, SUVL, BOVL,
                         BUVL, TEMP_LIMIT, PWR_LIMIT, MANUFACTURER_ID, DEVICE_ID})
    t[r] = 2;
  for (std::uint8_t r : {VSHUNT, VBUS, CURRENT, POWER}) t[r] = 3;
  for (std::uint8_t r : {ENERGY, CHARGE}) t[r] = 5;
  return t;
}();
}  // namespace

int regSize(std::uint8_t reg) noexcept { return reg < kRegSize.size() ? kRegSize[reg] : 0; }
}  // namespace ina228

using namespace ina228;

namespace {
constexpr std::uint64_t kMask40 = (std::uint64_t{1} << 40) - 1;
bool isReadOnly(std::uint8_t reg) {
  return (reg >= VSHUNT && reg <= CHARGE) || reg == MANUFACTURER_ID || reg == DEVICE_ID;
}
}  // namespace

void Ina228Model::reset() noexcept {
  config_ = 0x0000;
  codesValid_ = false;
  adcConfig_ = 0xFB68;
  shuntCal_ = 0x1000;
  tempco_ = 0;
  vshunt_ = vbus_ = current_ = 0;
  dietemp_ = 0;
  power_ = 0;
  energyAcc_ = chargeAcc_ = 0.0;
  diag_ = MEMSTAT;
  sovl_ = 0x7FFF;
  suvl_ = 0x8000;
  bovl_ = 0x7FFF;
  buvl_ = 0x0000;
  tempLimit_ = 0x7FFF;
  pwrLimit_ = 0xFFFF;
  limitActive_ = false;
  ptr_ = 0;
  restartConversions();  // power-on default is continuous bus + shunt + temperature
  refreshLimits();
}

std::uint64_t Ina228Model::peek(std::uint8_t reg) const noexcept {
  switch (reg) {
    case CONFIG:
      return config_;
    case ADC_CONFIG:
      return adcConfig_;
    case SHUNT_CAL:
      return shuntCal_;
    case SHUNT_TEMPCO:
      return tempco_;
    case VSHUNT:
      return reg20(vshunt_);
    case VBUS:
      return reg20(vbus_);
    case DIETEMP:
      return std::uint16_t(dietemp_);
    case CURRENT:
      return reg20(current_);
    case POWER:
      return power_;
    case ENERGY:
      return std::uint64_t(energyAcc_) & kMask40;  // integer part (>= 0)
    case CHARGE:
      return std::uint64_t(std::int64_t(chargeAcc_)) & kMask40;  // truncated toward 0
    case DIAG_ALRT:
      return diag_;
    case SOVL:
      return sovl_;
    case SUVL:
      return suvl_;
    case BOVL:
      return bovl_;
    case BUVL:
      return buvl_;
    case TEMP_LIMIT:
      return tempLimit_;
    case PWR_LIMIT:
      return pwrLimit_;
    case MANUFACTURER_ID:
      return 0x5449;
    case DEVICE_ID:
      return 0x2281;
    default:
      return 0;
  }
}

int Ina228Model::read(std::uint8_t* buf, std::size_t len) noexcept {
  const int size = regSize(ptr_);
  if (len == 0 || size == 0 || len > std::size_t(size)) {
    ++protocolErrors_;
    return EREMOTEIO;
  }
  const std::uint64_t v = peek(ptr_);
  // MSB first; a read shorter than the register gets its first bytes.
  for (std::size_t i = 0; i < len; ++i) buf[i] = std::uint8_t(v >> (8 * (size - 1 - int(i))));
  // Read side effects.
  if (ptr_ == DIAG_ALRT) {
    clearOnDiagRead();
  } else if (ptr_ == ENERGY) {
    diag_ &= ~ENERGYOF;
  } else if (ptr_ == CHARGE) {
    diag_ &= ~CHARGEOF;
  }
  return 0;
}

int Ina228Model::write(const std::uint8_t* buf, std::size_t len) noexcept {
  if (len == 0) {
    ++protocolErrors_;
    return EREMOTEIO;
  }
  const std::uint8_t reg = buf[0];
  const int size = regSize(reg);
  if (size == 0) {  // reserved pointer: not acknowledged
    ++protocolErrors_;
    return EREMOTEIO;
  }
  if (len == 1) {  // pointer only (a read follows)
    ptr_ = reg;
    return 0;
  }
  if (isReadOnly(reg) || len != std::size_t(1 + size)) {
    ++protocolErrors_;
    return EREMOTEIO;
  }
  ptr_ = reg;
  const std::uint16_t v = static_cast<std::uint16_t>((buf[1] << 8) | buf[2]);
  switch (reg) {
    case CONFIG:
      if (v & 0x8000) {  // RST: same as power-on, bit clears itself
        reset();
        return 0;
      }
      if (v & 0x4000) {  // RSTACC
        energyAcc_ = chargeAcc_ = 0.0;
        diag_ &= ~(ENERGYOF | CHARGEOF | MATHOF);
      }
      config_ = v & 0x3FF0;  // RST/RSTACC self-clear; bits 3:0 reserved
      codesValid_ = false;   // ADCRANGE sets the shunt LSB
      break;
    case ADC_CONFIG:
      adcConfig_ = v;
      restartConversions();
      break;
    case SHUNT_CAL:
      shuntCal_ = v & 0x7FFF;
      codesValid_ = false;  // the raw power code depends on it
      break;
    case SHUNT_TEMPCO:
      tempco_ = v & 0x3FFF;
      break;
    case DIAG_ALRT:
      // Only the four control bits are writable; the rest are status.
      diag_ = static_cast<std::uint16_t>((diag_ & 0x0FFF) | (v & 0xF000));
      limitActive_ = (diag_ & kLimitFlags) != 0;
      codesValid_ = false;  // SLOWALERT decides whether the raw power is needed
      break;
    case SOVL:
      sovl_ = v;
      break;
    case SUVL:
      suvl_ = v;
      break;
    case BOVL:
      bovl_ = v & 0x7FFF;
      break;
    case BUVL:
      buvl_ = v & 0x7FFF;
      break;
    case TEMP_LIMIT:
      tempLimit_ = v;
      break;
    case PWR_LIMIT:
      pwrLimit_ = v;
      break;
    default:
      break;
  }
  refreshLimits();  // any register write may move a limit or the active channels
  return 0;
}

}  // namespace xr::sim
