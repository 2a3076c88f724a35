#pragma once
// Register access helpers over the I2cBus seam for chips with an 8-bit
// register pointer and big-endian (MSB first) registers: INA228 and ADS1115
// (docs/sources.md D1.6, §2.5). Header-only, no allocation, noexcept.
#include <cstddef>
#include <cstdint>

#include "drivers/hal/i2c_bus.h"

namespace xr::i2creg {

// Write the pointer then read `len` bytes (one combined transaction with a
// repeated start). Returns 0 or errno.
inline int readBytes(I2cBus& bus, std::uint16_t addr, std::uint8_t reg, std::uint8_t* out,
                     std::size_t len) noexcept {
  std::uint8_t ptr = reg;
  I2cMsg msgs[2] = {{addr, false, &ptr, 1}, {addr, true, out, len}};
  return bus.transfer(msgs);
}

// Reads an MSB-first register of `bytes` (1..5) bytes into *value.
inline int readReg(I2cBus& bus, std::uint16_t addr, std::uint8_t reg, std::size_t bytes,
                   std::uint64_t* value) noexcept {
  std::uint8_t buf[8] = {};
  if (bytes == 0 || bytes > 5) return 22;  // EINVAL
  const int rc = readBytes(bus, addr, reg, buf, bytes);
  if (rc != 0) return rc;
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < bytes; ++i) v = (v << 8) | buf[i];
  *value = v;
  return 0;
}

inline int readReg16(I2cBus& bus, std::uint16_t addr, std::uint8_t reg, std::uint16_t* value) noexcept {
  std::uint64_t v = 0;
  const int rc = readReg(bus, addr, reg, 2, &v);
  if (rc == 0) *value = static_cast<std::uint16_t>(v);
  return rc;
}

// Pointer byte then the 16-bit value MSB first, in one write message.
inline int writeReg16(I2cBus& bus, std::uint16_t addr, std::uint8_t reg, std::uint16_t value) noexcept {
  std::uint8_t buf[3] = {reg, static_cast<std::uint8_t>(value >> 8), static_cast<std::uint8_t>(value & 0xFF)};
  I2cMsg msg{addr, false, buf, 3};
  return bus.transfer({&msg, 1});
}

}  // namespace xr::i2creg
