#pragma once
// INA228 register map and encodings (docs/sources.md D1). Pure constexpr
// helpers, tested directly and shared by nothing else: the simulator's chip
// model is written separately from the same facts so the two check each other.
#include <cstdint>

namespace xr::ina228 {

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

inline constexpr std::uint16_t kManufacturerTI = 0x5449;  // "TI"
inline constexpr std::uint16_t kDieId = 0x228;            // DEVICE_ID bits 15:4 (REV_ID varies)

// CONFIG bits (§1.2)
inline constexpr std::uint16_t CONFIG_RST = 1u << 15;
inline constexpr std::uint16_t CONFIG_RSTACC = 1u << 14;
inline constexpr std::uint16_t CONFIG_ADCRANGE = 1u << 4;

// DIAG_ALRT bits (§1.5)
inline constexpr std::uint16_t DIAG_ALATCH = 1u << 15;
inline constexpr std::uint16_t DIAG_CNVR = 1u << 14;
inline constexpr std::uint16_t DIAG_SLOWALERT = 1u << 13;
inline constexpr std::uint16_t DIAG_APOL = 1u << 12;
inline constexpr std::uint16_t DIAG_MATHOF = 1u << 9;
inline constexpr std::uint16_t DIAG_TMPOL = 1u << 7;
inline constexpr std::uint16_t DIAG_SHNTOL = 1u << 6;
inline constexpr std::uint16_t DIAG_SHNTUL = 1u << 5;
inline constexpr std::uint16_t DIAG_BUSOL = 1u << 4;
inline constexpr std::uint16_t DIAG_BUSUL = 1u << 3;
inline constexpr std::uint16_t DIAG_POL = 1u << 2;
inline constexpr std::uint16_t DIAG_CNVRF = 1u << 1;
inline constexpr std::uint16_t DIAG_MEMSTAT = 1u << 0;

// ADC_CONFIG fields (§1.3)
inline constexpr std::uint16_t MODE_CONT_BUS_SHUNT_TEMP = 0xF;
// Conversion-time codes: 0..7 = 50, 84, 150, 280, 540, 1052, 2074, 4120 µs.
inline constexpr int kConvTimeUs[8] = {50, 84, 150, 280, 540, 1052, 2074, 4120};
// Averaging codes: 0..7 = 1, 4, 16, 64, 128, 256, 512, 1024 samples.
inline constexpr int kAvgCount[8] = {1, 4, 16, 64, 128, 256, 512, 1024};

constexpr std::uint16_t adcConfig(unsigned mode, unsigned vbusct, unsigned vshct, unsigned vtct,
                                  unsigned avg) {
  return static_cast<std::uint16_t>(((mode & 0xF) << 12) | ((vbusct & 7) << 9) | ((vshct & 7) << 6) |
                                    ((vtct & 7) << 3) | (avg & 7));
}
// Time for one full (averaged) result set in continuous bus+shunt+temp mode, µs.
constexpr long adcCycleUs(std::uint16_t cfg) {
  const unsigned vbusct = (cfg >> 9) & 7, vshct = (cfg >> 6) & 7, vtct = (cfg >> 3) & 7, avg = cfg & 7;
  return static_cast<long>(kConvTimeUs[vbusct] + kConvTimeUs[vshct] + kConvTimeUs[vtct]) * kAvgCount[avg];
}

// Fast mode (field on, `inaFastModeActive`): 540 µs bus and shunt, 50 µs die
// temperature, 4 averages -> a result (and a SLOWALERT comparison) every
// ~4.5 ms, close to the specification's "~4.3 ms cycle".
inline constexpr std::uint16_t kAdcConfigFast = adcConfig(MODE_CONT_BUS_SHUNT_TEMP, 4, 4, 0, 1);
// Slow mode (field off): 4120 µs bus and shunt, 50 µs temp, 128 averages ->
// ~1.06 s, the specification's "~1054 ms" noise-free averaging while nothing drives the field.
inline constexpr std::uint16_t kAdcConfigSlow = adcConfig(MODE_CONT_BUS_SHUNT_TEMP, 7, 7, 0, 4);

// 20-bit two's complement in bits 23:4 of a 24-bit register -> signed code.
constexpr std::int32_t decode20(std::uint32_t raw24) {
  std::int32_t v = static_cast<std::int32_t>((raw24 >> 4) & 0xFFFFF);
  if (v & 0x80000) v -= 0x100000;
  return v;
}
constexpr std::uint32_t encode20(std::int32_t code) {
  return (static_cast<std::uint32_t>(code) & 0xFFFFF) << 4;
}

inline constexpr double kVbusLsbV = 195.3125e-6;   // VBUS
inline constexpr double kDieTempLsbC = 7.8125e-3;  // DIETEMP, full 16 bits signed
inline constexpr double kBovlLsbV = 3.125e-3;      // BOVL/BUVL, bits 14:0

constexpr double vbusVolts(std::uint32_t raw24) { return decode20(raw24) * kVbusLsbV; }
constexpr double dieTempC(std::uint16_t raw) { return static_cast<std::int16_t>(raw) * kDieTempLsbC; }

// CURRENT_LSB = maxCurrent / 2^19 (DS228 Eq. 3).
constexpr double currentLsb(double maxCurrentA) { return maxCurrentA / 524288.0; }
constexpr double currentAmps(std::uint32_t raw24, double lsb) { return decode20(raw24) * lsb; }

// ADCRANGE=1 (±40.96 mV) when the full-scale shunt voltage fits it, for 4x resolution.
constexpr bool useLowAdcRange(double shuntOhm, double maxCurrentA) {
  return shuntOhm * maxCurrentA <= 0.04096;
}

// SHUNT_CAL = 13107.2e6 * CURRENT_LSB * R_SHUNT (x4 with ADCRANGE=1). Returns
// -1 when it does not fit the 15-bit field or rounds to 0 (a configuration
// error: CURRENT would read 0 or wrap).
constexpr long shuntCal(double shuntOhm, double maxCurrentA, bool lowRange) {
  if (!(shuntOhm > 0.0) || !(maxCurrentA > 0.0)) return -1;
  double v = 13107.2e6 * currentLsb(maxCurrentA) * shuntOhm;
  if (lowRange) v *= 4.0;
  const long cal = static_cast<long>(v + 0.5);
  return (cal < 1 || cal > 0x7FFF) ? -1 : cal;
}

// BOVL code for a bus-voltage limit: 3.125 mV/LSB in bits 14:0, clamped.
constexpr std::uint16_t bovlCode(double volts) {
  if (!(volts > 0.0)) return 0;
  const double c = volts / kBovlLsbV + 0.5;
  return c >= 32767.0 ? 0x7FFF : static_cast<std::uint16_t>(c);
}
constexpr double bovlVolts(std::uint16_t code) { return (code & 0x7FFF) * kBovlLsbV; }

// DIAG_ALRT value we program: transparent (ALATCH=0) so the ALERT pin follows
// the condition as the specification describes; SLOWALERT (compare the averaged value);
// APOL=0 (active low, open drain, pulls GPIO4 low).
inline constexpr std::uint16_t kDiagAlrtConfig = DIAG_SLOWALERT;

}  // namespace xr::ina228
