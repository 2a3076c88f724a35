#pragma once
// Little-endian field access in a CAN payload (every protocol here is
// little-endian: the SMA/Victron BMS set, Pylontech, NMEA 2000).
#include <cstddef>
#include <cstdint>
#include <span>

namespace xr::can {

inline std::uint16_t getU16(std::span<const std::uint8_t> d, std::size_t at) {
  return static_cast<std::uint16_t>(d[at] | (d[at + 1] << 8));
}
inline std::int16_t getS16(std::span<const std::uint8_t> d, std::size_t at) {
  return static_cast<std::int16_t>(getU16(d, at));
}
inline void putU16(std::span<std::uint8_t> d, std::size_t at, std::uint16_t v) {
  d[at] = static_cast<std::uint8_t>(v & 0xFF);
  d[at + 1] = static_cast<std::uint8_t>(v >> 8);
}
inline void putS16(std::span<std::uint8_t> d, std::size_t at, std::int16_t v) {
  putU16(d, at, static_cast<std::uint16_t>(v));
}
inline std::uint32_t getU32(std::span<const std::uint8_t> d, std::size_t at) {
  return static_cast<std::uint32_t>(getU16(d, at)) | (static_cast<std::uint32_t>(getU16(d, at + 2)) << 16);
}
inline void putU32(std::span<std::uint8_t> d, std::size_t at, std::uint32_t v) {
  putU16(d, at, static_cast<std::uint16_t>(v & 0xFFFF));
  putU16(d, at + 2, static_cast<std::uint16_t>(v >> 16));
}

inline std::int32_t getS32(std::span<const std::uint8_t> d, std::size_t at) {
  return static_cast<std::int32_t>(getU32(d, at));
}
inline void putS32(std::span<std::uint8_t> d, std::size_t at, std::int32_t v) {
  putU32(d, at, static_cast<std::uint32_t>(v));
}
inline std::int64_t getS64(std::span<const std::uint8_t> d, std::size_t at) {
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(getU32(d, at)) |
                                   (static_cast<std::uint64_t>(getU32(d, at + 4)) << 32));
}
inline void putS64(std::span<std::uint8_t> d, std::size_t at, std::int64_t v) {
  const auto u = static_cast<std::uint64_t>(v);
  putU32(d, at, static_cast<std::uint32_t>(u & 0xFFFFFFFFu));
  putU32(d, at + 4, static_cast<std::uint32_t>(u >> 32));
}

}  // namespace xr::can
