#pragma once
// ADS1115 register map and encodings (docs/sources.md D2). Pure constexpr.
#include <cstdint>

namespace xr::ads1115 {

enum Reg : std::uint8_t { CONVERSION = 0x00, CONFIG = 0x01, LO_THRESH = 0x02, HI_THRESH = 0x03 };

inline constexpr std::uint16_t OS = 1u << 15;
inline constexpr std::uint16_t MODE_SINGLE = 1u << 8;  // 0 = continuous
inline constexpr unsigned DR_860 = 7;                  // bits 7:5
inline constexpr unsigned COMP_QUE_DISABLE = 3;        // bits 1:0
inline constexpr unsigned COMP_QUE_ONE = 0;

// PGA codes and full-scale ranges (V): 0=6.144, 1=4.096, 2=2.048, 3=1.024, 4=0.512, 5..7=0.256.
// (Namespace-scope table: a table local to the function is rebuilt on the
// stack at every call, ~860 times a second.)
inline constexpr double kFullScaleVolts[8] = {6.144, 4.096, 2.048, 1.024, 0.512, 0.256, 0.256, 0.256};
constexpr double fullScaleVolts(unsigned pga) { return kFullScaleVolts[pga & 7]; }
// Data rates (SPS) by DR code.
constexpr int dataRateSps(unsigned dr) {
  constexpr int sps[8] = {8, 16, 32, 64, 128, 250, 475, 860};
  return sps[dr & 7];
}
// Single-ended AINx vs GND: MUX = 100 + x.
constexpr unsigned muxSingleEnded(int channel) { return 4u + (static_cast<unsigned>(channel) & 3u); }

// Config for continuous conversion of one single-ended channel. With
// `readyPin` the comparator is enabled (COMP_QUE=00) with Hi_thresh MSB=1 and
// Lo_thresh MSB=0 so ALERT/RDY pulses after each conversion (§2.3);
// otherwise the comparator is disabled (COMP_QUE=11).
constexpr std::uint16_t configContinuous(int channel, unsigned pga, unsigned dr, bool readyPin) {
  return static_cast<std::uint16_t>((muxSingleEnded(channel) << 12) | ((pga & 7) << 9) | ((dr & 7) << 5) |
                                    (readyPin ? COMP_QUE_ONE : COMP_QUE_DISABLE));
}
constexpr int muxChannelOf(std::uint16_t config) {
  const unsigned mux = (config >> 12) & 7;
  return mux >= 4 ? static_cast<int>(mux - 4) : -1;
}

// ALERT/RDY as conversion-ready: Hi_thresh = 0x8000, Lo_thresh = 0x0000.
inline constexpr std::uint16_t kReadyHiThresh = 0x8000;
inline constexpr std::uint16_t kReadyLoThresh = 0x0000;

// Volts per code, FSR / 2^15. Kept per channel by the driver (one multiply
// per conversion instead of two table lookups).
constexpr double voltsPerCode(unsigned pga) { return fullScaleVolts(pga) / 32768.0; }
// Conversion code (16-bit two's complement) -> volts at the input. Equal bit
// for bit to code * FSR / 2^15: the division by 2^15 is exact on either side
// of the one rounded product (a test compares every code at every PGA).
constexpr double codeToVolts(std::uint16_t raw, unsigned pga) {
  return static_cast<std::int16_t>(raw) * voltsPerCode(pga);
}

}  // namespace xr::ads1115
