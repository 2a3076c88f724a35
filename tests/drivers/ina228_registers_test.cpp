// INA228 encodings against the worked example of docs/sources.md, datasheet facts §1.4 (TI
// INA229 sibling: Imax 10 A) and the register layout facts.
#include "drivers/ina228/ina228_registers.h"

#include <gtest/gtest.h>

namespace xr::ina228 {
namespace {

TEST(Ina228Registers, WorkedExampleCurrentVbusDietemp) {
  const double lsb = currentLsb(10.0);
  EXPECT_NEAR(lsb, 19.073486e-6, 1e-12);
  EXPECT_NEAR(currentAmps(encode20(314572), lsb), 6.0, 1e-4);
  EXPECT_NEAR(vbusVolts(encode20(245760)), 48.0, 1e-9);
  EXPECT_NEAR(dieTempC(3200), 25.0, 1e-9);
}

TEST(Ina228Registers, TwentyBitFieldsAreSignExtendedFromBit19) {
  EXPECT_EQ(decode20(0xFFFFF0), -1);
  EXPECT_EQ(decode20(0x800000), -524288);
  EXPECT_EQ(decode20(0x7FFFF0), 524287);
  EXPECT_EQ(decode20(0x00000F), 0) << "bits 3:0 are reserved";
  EXPECT_NEAR(currentAmps(encode20(-314572), currentLsb(10.0)), -6.0, 1e-4);
}

TEST(Ina228Registers, DieTempUsesAllSixteenBits) {
  // facts §1.8: full 16 bits at 7.8125 m°C, not the INA238 bits 15:4 layout.
  EXPECT_NEAR(dieTempC(0xFF80), -1.0, 1e-9);
  EXPECT_NEAR(dieTempC(1), 0.0078125, 1e-12);
}

TEST(Ina228Registers, ShuntCalForTheDefaultShunt) {
  // 500 µΩ, 200 A: LSB = 200/2^19, CAL = 13107.2e6 * LSB * R = 2500.
  EXPECT_FALSE(useLowAdcRange(0.0005, 200.0));
  EXPECT_EQ(shuntCal(0.0005, 200.0, false), 2500);
  // 40.96 mV full scale or less: ADCRANGE=1 and CAL x4.
  EXPECT_TRUE(useLowAdcRange(0.0002, 200.0));
  EXPECT_EQ(shuntCal(0.0002, 200.0, true), 4000);
}

TEST(Ina228Registers, ShuntCalRejectsValuesThatDoNotFit) {
  EXPECT_EQ(shuntCal(0.0, 200.0, false), -1);
  EXPECT_EQ(shuntCal(0.0005, -1.0, false), -1);
  EXPECT_EQ(shuntCal(1.0, 1000.0, false), -1) << "above 15 bits";
  EXPECT_EQ(shuntCal(1e-9, 1e-3, false), -1) << "rounds to 0";
}

TEST(Ina228Registers, BovlCodeIs3125MicrovoltsPerLsbClamped) {
  EXPECT_EQ(bovlCode(14.8), 4736);
  EXPECT_NEAR(bovlVolts(bovlCode(14.8)), 14.8, 0.0016);
  EXPECT_EQ(bovlCode(200.0), 0x7FFF);
  EXPECT_EQ(bovlCode(-1.0), 0);
}

TEST(Ina228Registers, FastAndSlowModeCycleTimes) {
  EXPECT_EQ(kAdcConfigFast >> 12, 0xF);
  EXPECT_EQ(adcCycleUs(kAdcConfigFast), (540 + 540 + 50) * 4);
  EXPECT_EQ(adcCycleUs(kAdcConfigSlow), (4120 + 4120 + 50) * 128);
  EXPECT_EQ(adcCycleUs(0xFB68), 1052 * 3) << "reset value: 1052 µs each, 1 average";
}

}  // namespace
}  // namespace xr::ina228
