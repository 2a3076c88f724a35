// INA228 model against docs/sources.md, datasheet facts §1 (register map, encodings, alerts).
#include "drivers/sim/ina228_model.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <cstdint>
#include <vector>

#include "drivers/sim/sim_i2c_bus.h"

namespace xr::sim {
namespace {
using namespace ina228;

struct Rig {
  TimeNs now = 0;
  SimI2cBus bus{&now};
  Ina228Model chip;
  Rig() { bus.attach(0x40, &chip); }
  int writeReg(std::uint8_t reg, std::uint16_t v) {
    std::uint8_t b[3] = {reg, std::uint8_t(v >> 8), std::uint8_t(v)};
    I2cMsg m{0x40, false, b, 3};
    return bus.transfer({&m, 1});
  }
  // Pointer write + read of n bytes in one combined transaction.
  std::uint64_t readReg(std::uint8_t reg, int n, int* rc = nullptr) {
    std::uint8_t p = reg;
    std::uint8_t buf[8] = {};
    I2cMsg m[2] = {{0x40, false, &p, 1}, {0x40, true, buf, std::size_t(n)}};
    const int r = bus.transfer(m);
    if (rc) *rc = r;
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v = (v << 8) | buf[i];
    return v;
  }
  void advance(TimeNs dt) {
    now += dt;
    chip.update(now);
  }
};

TEST(Ina228Model, ResetValuesMatchDatasheet) {
  Rig r;
  EXPECT_EQ(r.readReg(CONFIG, 2), 0x0000u);
  EXPECT_EQ(r.readReg(ADC_CONFIG, 2), 0xFB68u);
  EXPECT_EQ(r.readReg(SHUNT_CAL, 2), 0x1000u);
  EXPECT_EQ(r.readReg(DIAG_ALRT, 2), 0x0001u);
  EXPECT_EQ(r.readReg(SOVL, 2), 0x7FFFu);
  EXPECT_EQ(r.readReg(SUVL, 2), 0x8000u);
  EXPECT_EQ(r.readReg(BOVL, 2), 0x7FFFu);
  EXPECT_EQ(r.readReg(BUVL, 2), 0x0000u);
  EXPECT_EQ(r.readReg(TEMP_LIMIT, 2), 0x7FFFu);
  EXPECT_EQ(r.readReg(PWR_LIMIT, 2), 0xFFFFu);
  EXPECT_EQ(r.readReg(MANUFACTURER_ID, 2), 0x5449u);
  EXPECT_EQ(r.readReg(DEVICE_ID, 2), 0x2281u);
  EXPECT_EQ(r.readReg(ENERGY, 5), 0u);
}

TEST(Ina228Model, RejectsWritesToReadOnlyAndReservedRegisters) {
  Rig r;
  EXPECT_EQ(r.writeReg(VBUS, 0x1234), EREMOTEIO);
  EXPECT_EQ(r.writeReg(MANUFACTURER_ID, 0), EREMOTEIO);
  EXPECT_EQ(r.writeReg(0x20, 0), EREMOTEIO);  // reserved address
  int rc = 0;
  r.readReg(0x12, 2, &rc);  // bad pointer
  EXPECT_EQ(rc, EREMOTEIO);
  r.readReg(VBUS, 4, &rc);  // longer than the register
  EXPECT_EQ(rc, EREMOTEIO);
  // Wrong data length for a 16-bit register.
  std::uint8_t b[2] = {SHUNT_CAL, 0x10};
  I2cMsg m{0x40, false, b, 2};
  EXPECT_EQ(r.bus.transfer({&m, 1}), EREMOTEIO);
  EXPECT_EQ(r.chip.protocolErrors(), 6u);
  EXPECT_EQ(r.writeReg(SHUNT_CAL, 0x0FA0), 0);
  EXPECT_EQ(r.chip.protocolErrors(), 6u);
}

TEST(Ina228Model, ReservedBitsReadZero) {
  Rig r;
  r.writeReg(SHUNT_CAL, 0xFFFF);
  EXPECT_EQ(r.readReg(SHUNT_CAL, 2), 0x7FFFu);
  r.writeReg(SHUNT_TEMPCO, 0xFFFF);
  EXPECT_EQ(r.readReg(SHUNT_TEMPCO, 2), 0x3FFFu);
  r.writeReg(BOVL, 0xFFFF);
  EXPECT_EQ(r.readReg(BOVL, 2), 0x7FFFu);
  r.writeReg(CONFIG, 0x000F | 0x0010);
  EXPECT_EQ(r.readReg(CONFIG, 2), 0x0010u);
}

TEST(Ina228Model, DatasheetWorkedExampleScaling) {
  // TI229W example: CURRENT_LSB = 10 A / 2^19, shunt 16.2 mΩ -> SHUNT_CAL 4050;
  // 97.2 mV shunt, 48 V bus.
  Rig r;
  r.writeReg(SHUNT_CAL, 4050);
  r.chip.setAnalog({0.0972, 48.0, 25.0});
  r.writeReg(ADC_CONFIG, 0xFB68);  // restart
  r.advance(r.chip.updatePeriod());
  EXPECT_EQ(r.readReg(VSHUNT, 3) >> 4, 311040u);
  EXPECT_EQ(r.readReg(VBUS, 3) >> 4, 245760u);
  EXPECT_EQ(r.readReg(DIETEMP, 2), 3200u);
  EXPECT_NEAR(double(r.readReg(CURRENT, 3) >> 4), 314572.0, 1.0);
  EXPECT_NEAR(double(r.readReg(POWER, 3)), 4718604.0, 40.0);
}

TEST(Ina228Model, EnergyAndChargeAccumulate) {
  Rig r;
  r.writeReg(SHUNT_CAL, 4050);
  r.chip.setAnalog({0.0972, 48.0, 25.0});
  r.writeReg(ADC_CONFIG, 0xFB68);
  r.advance(fromSec(3600.0));
  // 6 A x 1 h = 21600 C = 1132462080 codes; 288 W h = 1036800 J.
  EXPECT_NEAR(double(r.readReg(CHARGE, 5)), 1132462080.0, 1132462080.0 * 1e-3);
  EXPECT_NEAR(double(r.readReg(ENERGY, 5)), 1061683200.0, 1061683200.0 * 1e-3);
  r.writeReg(CONFIG, 0x4000);  // RSTACC
  EXPECT_EQ(r.readReg(CHARGE, 5), 0u);
  EXPECT_EQ(r.readReg(CONFIG, 2), 0u);  // self-clearing
}

TEST(Ina228Model, NegativeCurrentIsTwosComplement) {
  Rig r;
  r.writeReg(SHUNT_CAL, 4096);
  r.chip.setAnalog({-0.001, 12.0, 25.0});
  r.writeReg(ADC_CONFIG, 0xFB68);
  r.advance(r.chip.updatePeriod());
  const std::uint32_t raw = std::uint32_t(r.readReg(VSHUNT, 3) >> 4);
  const std::int32_t code = (raw & 0x80000) ? std::int32_t(raw) - (1 << 20) : std::int32_t(raw);
  EXPECT_EQ(code, -3200);  // -1 mV / 312.5 nV
  const std::uint32_t cur = std::uint32_t(r.readReg(CURRENT, 3) >> 4);
  EXPECT_TRUE(cur & 0x80000);
}

TEST(Ina228Model, AdcRangeOneQuadruplesResolution) {
  Rig r;
  r.writeReg(CONFIG, 0x0010);
  r.chip.setAnalog({0.001, 12.0, 25.0});
  r.writeReg(ADC_CONFIG, 0xFB68);
  r.advance(r.chip.updatePeriod());
  EXPECT_EQ(r.readReg(VSHUNT, 3) >> 4, 12800u);  // 1 mV / 78.125 nV
}

TEST(Ina228Model, ConversionTimeTimesAveragingSetsCadence) {
  Rig r;
  // Continuous bus+shunt (0xB), VBUSCT=VSHCT=4 (540 us), AVG=2 (16).
  const std::uint16_t cfg = (0xB << 12) | (4 << 9) | (4 << 6) | (0 << 3) | 2;
  r.writeReg(ADC_CONFIG, cfg);
  EXPECT_EQ(r.chip.updatePeriod(), fromUs((540 + 540) * 16));
  r.chip.setAnalog({0.0, 13.0, 25.0});
  const auto before = r.chip.conversions();
  r.advance(fromUs(1080 * 16) - 1);
  EXPECT_EQ(r.chip.conversions(), before);
  EXPECT_EQ(r.readReg(VBUS, 3), 0u);  // nothing published yet
  r.advance(1);
  EXPECT_EQ(r.chip.conversions(), before + 1);
  EXPECT_EQ(r.readReg(VBUS, 3) >> 4, 66560u);  // 13 V / 195.3125 uV
  // Conversion-time code 7 is 4120 us.
  r.writeReg(ADC_CONFIG, (0x9 << 12) | (7 << 9));
  EXPECT_EQ(r.chip.updatePeriod(), fromUs(4120));
}

TEST(Ina228Model, TriggeredModeConvertsOnceThenStops) {
  Rig r;
  r.chip.setAnalog({0.0, 12.5, 25.0});
  r.writeReg(ADC_CONFIG, (0x1 << 12) | (5 << 9));  // triggered bus, 1052 us
  r.advance(fromMs(10));
  EXPECT_EQ(r.readReg(VBUS, 3) >> 4, 64000u);
  r.chip.setAnalog({0.0, 13.0, 25.0});
  r.advance(fromMs(10));
  EXPECT_EQ(r.readReg(VBUS, 3) >> 4, 64000u);  // no new conversion
}

TEST(Ina228Model, ShutdownModeHoldsRegisters) {
  Rig r;
  r.writeReg(ADC_CONFIG, 0x0000);
  EXPECT_EQ(r.chip.updatePeriod(), 0);
  r.chip.setAnalog({0.0, 12.0, 25.0});
  r.advance(fromMs(100));
  EXPECT_EQ(r.readReg(VBUS, 3), 0u);
  EXPECT_EQ(r.writeReg(BOVL, 100), 0);  // registers stay writable
}

TEST(Ina228Model, BusOvervoltageAssertsAlertTransparent) {
  Rig r;
  r.writeReg(ADC_CONFIG, (0x9 << 12) | (0 << 9));  // continuous bus, 50 us, 1 avg
  r.writeReg(BOVL, std::uint16_t(14.8 / 3.125e-3));
  r.chip.setAnalog({0.0, 14.0, 25.0});
  r.advance(fromMs(1));
  EXPECT_FALSE(r.chip.alertActive());
  EXPECT_TRUE(r.chip.alertPinHigh());
  r.chip.setAnalog({0.0, 15.0, 25.0});
  r.advance(fromMs(1));
  EXPECT_TRUE(r.chip.alertActive());
  EXPECT_FALSE(r.chip.alertPinHigh());  // active low by default
  EXPECT_TRUE(r.readReg(DIAG_ALRT, 2) & BUSOL);
  // Transparent: clears when the condition clears.
  r.chip.setAnalog({0.0, 14.0, 25.0});
  r.advance(fromMs(1));
  EXPECT_FALSE(r.chip.alertActive());
  EXPECT_FALSE(r.readReg(DIAG_ALRT, 2) & BUSOL);
}

TEST(Ina228Model, LatchedAlertHoldsUntilDiagRead) {
  Rig r;
  r.writeReg(ADC_CONFIG, (0x9 << 12));
  r.writeReg(DIAG_ALRT, ALATCH);
  r.writeReg(BOVL, std::uint16_t(14.8 / 3.125e-3));
  r.chip.setAnalog({0.0, 15.0, 25.0});
  r.advance(fromMs(1));
  r.chip.setAnalog({0.0, 14.0, 25.0});
  r.advance(fromMs(1));
  EXPECT_TRUE(r.chip.alertActive());
  const auto d = r.readReg(DIAG_ALRT, 2);
  EXPECT_TRUE(d & BUSOL);
  EXPECT_TRUE(d & ALATCH);
  EXPECT_FALSE(r.chip.alertActive());
}

TEST(Ina228Model, SlowAlertComparesTheAveragedValue) {
  // 64 averages x 1052 us: with SLOWALERT the alert waits for the average;
  // without it the first raw sample over the limit asserts.
  for (bool slow : {false, true}) {
    Rig r;
    r.writeReg(DIAG_ALRT, slow ? SLOWALERT : 0);
    r.writeReg(BOVL, std::uint16_t(14.8 / 3.125e-3));
    r.chip.setAnalog({0.0, 15.0, 25.0});
    r.writeReg(ADC_CONFIG, (0x9 << 12) | (5 << 9) | 3);
    r.advance(fromUs(1052 * 2));
    EXPECT_EQ(r.chip.alertActive(), !slow) << "slow=" << slow;
    r.advance(fromUs(1052 * 64));
    EXPECT_TRUE(r.chip.alertActive());
  }
}

TEST(Ina228Model, ApolInvertsThePin) {
  Rig r;
  r.writeReg(DIAG_ALRT, APOL);
  EXPECT_FALSE(r.chip.alertPinHigh());  // inactive, inverted = low
  r.writeReg(ADC_CONFIG, (0x9 << 12));
  r.writeReg(BOVL, 100);
  r.chip.setAnalog({0.0, 12.0, 25.0});
  r.advance(fromMs(1));
  EXPECT_TRUE(r.chip.alertPinHigh());
}

TEST(Ina228Model, ResetBitRestoresDefaults) {
  Rig r;
  r.writeReg(SHUNT_CAL, 1234);
  r.writeReg(BOVL, 10);
  r.writeReg(CONFIG, 0x8000);
  EXPECT_EQ(r.readReg(SHUNT_CAL, 2), 0x1000u);
  EXPECT_EQ(r.readReg(BOVL, 2), 0x7FFFu);
  EXPECT_EQ(r.readReg(CONFIG, 2), 0u);
}

TEST(Ina228Model, ConvdlyDelaysFirstConversion) {
  Rig r;
  r.writeReg(CONFIG, 5 << 6);  // 10 ms
  r.chip.setAnalog({0.0, 12.0, 25.0});
  r.writeReg(ADC_CONFIG, (0x9 << 12));  // 50 us
  r.advance(fromMs(9));
  EXPECT_EQ(r.chip.conversions(), 0u);
  r.advance(fromMs(2));
  EXPECT_GT(r.chip.conversions(), 0u);
}

TEST(SimI2cBus, AbsentOrNackedChipFailsLikeI2cDev) {
  Rig r;
  std::uint8_t p = 0;
  I2cMsg m{0x41, false, &p, 1};
  EXPECT_EQ(r.bus.transfer({&m, 1}), EREMOTEIO);
  r.bus.setNack(0x40, true);
  int rc = 0;
  r.readReg(MANUFACTURER_ID, 2, &rc);
  EXPECT_EQ(rc, EREMOTEIO);
  r.bus.setNack(0x40, false);
  EXPECT_EQ(r.readReg(MANUFACTURER_ID, 2, &rc), 0x5449u);
  EXPECT_EQ(rc, 0);
  EXPECT_EQ(r.bus.failedTransfers(), 2u);
}

TEST(Ina228Model, PointerIsRetainedBetweenReads) {
  Rig r;
  std::uint8_t p = MANUFACTURER_ID;
  I2cMsg w{0x40, false, &p, 1};
  ASSERT_EQ(r.bus.transfer({&w, 1}), 0);
  std::uint8_t buf[2] = {};
  I2cMsg rd{0x40, true, buf, 2};
  ASSERT_EQ(r.bus.transfer({&rd, 1}), 0);
  EXPECT_EQ(buf[0], 0x54);
  EXPECT_EQ(buf[1], 0x49);
}

// The driver's poll (pointer + read pairs for DIAG_ALRT, VBUS, CURRENT) has
// a fast path in transact(): the bytes, the DIAG_ALRT read side effect
// (latched flags clear) and the retained pointer must be those of the same
// messages sent one by one; a pair it does not know goes the general way.
TEST(Ina228Model, PollTransactionMatchesMessagesOneByOne) {
  Rig a, b;
  for (Rig* r : {&a, &b}) {
    r->writeReg(ADC_CONFIG, (0xB << 12) | (1 << 9) | (1 << 6));  // bus + shunt, 84 us, 1 avg
    r->writeReg(DIAG_ALRT, ALATCH);
    r->writeReg(BOVL, std::uint16_t(14.8 / 3.125e-3));
  }
  const double vbus[] = {14.0, 15.0, 14.0, 14.2, -0.5};
  const double vsh[] = {0.01, -0.02, 0.03, 0.0, 0.001};
  for (int i = 0; i < 5; ++i) {
    for (Rig* r : {&a, &b}) {
      r->chip.setAnalog({vsh[i], vbus[i], 25.0});
      r->advance(fromUs(500));
    }
    std::uint8_t pa[3] = {DIAG_ALRT, VBUS, CURRENT}, ra[8] = {};
    I2cMsg ma[6] = {{0x40, false, &pa[0], 1}, {0x40, true, ra, 2},      {0x40, false, &pa[1], 1},
                    {0x40, true, ra + 2, 3},  {0x40, false, &pa[2], 1}, {0x40, true, ra + 5, 3}};
    ASSERT_EQ(a.bus.transfer(ma), 0);
    std::uint8_t pb[3] = {DIAG_ALRT, VBUS, CURRENT}, rb[8] = {};
    I2cMsg mb[6] = {{0x40, false, &pb[0], 1}, {0x40, true, rb, 2},      {0x40, false, &pb[1], 1},
                    {0x40, true, rb + 2, 3},  {0x40, false, &pb[2], 1}, {0x40, true, rb + 5, 3}};
    for (I2cMsg& m : mb) ASSERT_EQ(b.bus.transfer({&m, 1}), 0);
    for (int k = 0; k < 8; ++k) EXPECT_EQ(ra[k], rb[k]) << "i=" << i << " byte " << k;
    EXPECT_EQ(a.chip.peek(DIAG_ALRT), b.chip.peek(DIAG_ALRT));
    EXPECT_EQ(a.chip.alertActive(), b.chip.alertActive());
    // The retained pointer (CURRENT): a read without a pointer write.
    std::uint8_t xa[3] = {}, xb[3] = {};
    I2cMsg rda{0x40, true, xa, 3}, rdb{0x40, true, xb, 3};
    ASSERT_EQ(a.bus.transfer({&rda, 1}), 0);
    ASSERT_EQ(b.bus.transfer({&rdb, 1}), 0);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(xa[k], xb[k]);
  }
  // DIAG_ALRT, then a pair the fast path does not take (POWER) and a read
  // longer than the register: refused after the first pair took effect.
  std::uint8_t p[2] = {DIAG_ALRT, POWER}, rx[8] = {};
  I2cMsg m[4] = {
      {0x40, false, &p[0], 1}, {0x40, true, rx, 2}, {0x40, false, &p[1], 1}, {0x40, true, rx + 2, 4}};
  const std::uint64_t errors = a.chip.protocolErrors();
  EXPECT_EQ(a.bus.transfer(m), EREMOTEIO);
  EXPECT_EQ(a.chip.protocolErrors(), errors + 1);
  EXPECT_EQ(std::uint16_t((rx[0] << 8) | rx[1]), a.chip.peek(DIAG_ALRT));  // no sample since the last read
}

// update() sums one raw sample inline when it ends no window and SLOWALERT
// = 1: a chip updated every few microseconds must end up exactly where one
// updated only when its inputs change does (the same inputs for the same
// samples), through SLOWALERT switches and an ADC_CONFIG restart.
TEST(Ina228Model, FineUpdatesMatchCoarseUpdates) {
  Rig fine, coarse;
  for (Rig* r : {&fine, &coarse}) {
    r->writeReg(DIAG_ALRT, SLOWALERT);
    r->writeReg(BOVL, std::uint16_t(14.5 / 3.125e-3));
    r->writeReg(ADC_CONFIG, (0xF << 12) | (1 << 9) | (1 << 6) | (0 << 3) | 2);  // 84+84+50 us, 16 avg
  }
  TimeNs t = 0;
  for (int i = 0; i < 200; ++i) {
    const Ina228Analog a{0.001 * (i % 7) - 0.002, 13.0 + 0.01 * (i % 13) + (i % 50 > 40 ? 2.0 : 0.0),
                         25.0 + 0.5 * (i / 60)};
    fine.chip.setAnalog(a);
    coarse.chip.setAnalog(a);
    const TimeNs next = t + fromUs(700 + 37 * (i % 5));
    for (TimeNs u = t + fromUs(23); u < next; u += fromUs(23)) fine.chip.update(u);
    t = next;
    fine.now = coarse.now = t;
    fine.chip.update(t);
    coarse.chip.update(t);
    if (i == 70 || i == 120) {  // SLOWALERT off, then on again (through the bus, as the driver would)
      for (Rig* r : {&fine, &coarse}) r->writeReg(DIAG_ALRT, i == 70 ? 0 : SLOWALERT);
    }
    if (i == 150) {
      for (Rig* r : {&fine, &coarse}) r->writeReg(ADC_CONFIG, (0xF << 12) | (2 << 9) | (1 << 6) | 1);
    }
    for (std::uint8_t reg : {VSHUNT, VBUS, DIETEMP, CURRENT, POWER, ENERGY, CHARGE, DIAG_ALRT})
      ASSERT_EQ(fine.chip.peek(reg), coarse.chip.peek(reg)) << "i=" << i << " reg " << int(reg);
    ASSERT_EQ(fine.chip.conversions(), coarse.chip.conversions()) << "i=" << i;
  }
  EXPECT_GT(fine.chip.conversions(), 40u);
}

}  // namespace
}  // namespace xr::sim

namespace xr::sim {
namespace {
using namespace ina228;

TEST(Ina228Model, CnvrPutsConversionReadyOnTheAlertPin) {
  Rig r;
  r.writeReg(DIAG_ALRT, CNVR | ALATCH);
  r.writeReg(ADC_CONFIG, (0x9 << 12));  // bus only, 50 us
  r.chip.setAnalog({0.0, 12.0, 25.0});
  EXPECT_FALSE(r.chip.alertActive());
  r.advance(fromUs(60));
  EXPECT_TRUE(r.chip.alertActive());
  EXPECT_TRUE(r.readReg(DIAG_ALRT, 2) & CNVRF);
  EXPECT_FALSE(r.chip.alertActive());  // the read cleared CNVRF
}

TEST(Ina228Model, PowerLimitAndShuntLimitsFlag) {
  Rig r;
  r.writeReg(SHUNT_CAL, 4096);
  r.writeReg(ADC_CONFIG, (0xB << 12));  // bus + shunt, 50 us each
  r.writeReg(SOVL, 200);                // 200 x 5 uV = 1 mV
  r.writeReg(SUVL, std::uint16_t(-200));
  r.writeReg(PWR_LIMIT, 1);
  r.chip.setAnalog({0.002, 12.0, 25.0});
  r.advance(fromUs(200));
  auto d = r.readReg(DIAG_ALRT, 2);
  EXPECT_TRUE(d & SHNTOL);
  EXPECT_TRUE(d & POL);
  EXPECT_FALSE(d & SHNTUL);
  r.chip.setAnalog({-0.002, 12.0, 25.0});
  r.advance(fromUs(200));
  d = r.readReg(DIAG_ALRT, 2);
  EXPECT_TRUE(d & SHNTUL);
  EXPECT_FALSE(d & SHNTOL);
}

TEST(Ina228Model, TempLimitComparesDieTemperature) {
  Rig r;
  r.writeReg(ADC_CONFIG, (0xC << 12));  // temperature only
  r.writeReg(TEMP_LIMIT, std::uint16_t(80.0 / 7.8125e-3));
  r.chip.setAnalog({0.0, 0.0, 85.0});
  r.advance(fromMs(3));
  EXPECT_TRUE(r.readReg(DIAG_ALRT, 2) & TMPOL);
  EXPECT_EQ(r.readReg(DIETEMP, 2), std::uint64_t(85.0 / 7.8125e-3));
}

TEST(Ina228Model, ZeroShuntCalReadsZeroCurrent) {
  Rig r;
  r.writeReg(SHUNT_CAL, 0);
  r.chip.setAnalog({0.01, 12.0, 25.0});
  r.writeReg(ADC_CONFIG, 0xFB68);
  r.advance(fromMs(10));
  EXPECT_NE(r.readReg(VSHUNT, 3), 0u);
  EXPECT_EQ(r.readReg(CURRENT, 3), 0u);
  EXPECT_EQ(r.readReg(POWER, 3), 0u);
}

TEST(Ina228Model, CurrentOverflowSetsMathof) {
  Rig r;
  r.writeReg(SHUNT_CAL, 1);  // absurdly small calibration: CURRENT overflows 20 bits
  r.chip.setAnalog({0.1, 12.0, 25.0});
  r.writeReg(ADC_CONFIG, 0xFB68);
  r.advance(fromMs(10));
  EXPECT_TRUE(r.readReg(DIAG_ALRT, 2) & MATHOF);
  EXPECT_EQ(r.readReg(CURRENT, 3) >> 4, 0x7FFFFu);  // clamped at +full scale
}

TEST(Ina228Model, TempcoCompensationLowersCurrentWhenHot) {
  Rig cold, hot;
  for (Rig* r : {&cold, &hot}) {
    r->writeReg(SHUNT_CAL, 4096);
    r->writeReg(CONFIG, 0x0020);  // TEMPCOMP
    r->writeReg(SHUNT_TEMPCO, 1000);
  }
  cold.chip.setAnalog({0.01, 12.0, 25.0});
  hot.chip.setAnalog({0.01, 12.0, 125.0});
  for (Rig* r : {&cold, &hot}) {
    r->writeReg(ADC_CONFIG, 0xFB68);
    r->advance(fromMs(10));
  }
  const double c = double(cold.readReg(CURRENT, 3) >> 4), h = double(hot.readReg(CURRENT, 3) >> 4);
  EXPECT_NEAR(h / c, 1.0 / 1.1, 1e-3);  // +100 degC x 1000 ppm = +10 % R
}

TEST(Ina228Model, WindowAverageIsTheRoundedMeanOfItsRawSamples) {
  Rig r;
  r.writeReg(ADC_CONFIG, (0x9 << 12) | 1);  // bus only, 50 us, AVG=1 (4 samples)
  const double lsb = 195.3125e-6;
  // Samples at 50, 100 us see code 100; at 150, 200 us code 101: mean 100.5,
  // ties to even -> 100. Then 101, 101, 102, 102: 101.5 -> 102.
  r.chip.setAnalog({0.0, 100 * lsb, 25.0});
  r.advance(fromUs(100));
  r.chip.setAnalog({0.0, 101 * lsb, 25.0});
  r.advance(fromUs(100));
  EXPECT_EQ(r.chip.conversions(), 1u);
  EXPECT_EQ(r.readReg(VBUS, 3) >> 4, 100u);
  r.advance(fromUs(100));
  r.chip.setAnalog({0.0, 102 * lsb, 25.0});
  r.advance(fromUs(100));
  EXPECT_EQ(r.chip.conversions(), 2u);
  EXPECT_EQ(r.readReg(VBUS, 3) >> 4, 102u);
  // Negative shunt codes average the same way (two's complement, 20 bits).
  r.writeReg(ADC_CONFIG, (0xA << 12) | 1);  // shunt only
  r.chip.setAnalog({-3 * 312.5e-9, 0.0, 25.0});
  r.advance(fromUs(100));
  r.chip.setAnalog({-4 * 312.5e-9, 0.0, 25.0});
  r.advance(fromUs(100));
  EXPECT_EQ(r.readReg(VSHUNT, 3) >> 4, 0xFFFFCu);  // -3.5 -> -4
}

TEST(Ina228Model, ClearingSlowAlertComparesRawSamplesAtOnce) {
  Rig r;
  r.writeReg(SHUNT_CAL, 4096);
  r.writeReg(PWR_LIMIT, 1);
  r.writeReg(DIAG_ALRT, SLOWALERT);
  r.writeReg(ADC_CONFIG, (0xB << 12) | 7);  // bus + shunt, 50 us, 1024 samples: no result for ~100 ms
  r.chip.setAnalog({0.002, 12.0, 25.0});
  r.advance(fromUs(500));
  EXPECT_FALSE(r.readReg(DIAG_ALRT, 2) & POL) << "SLOWALERT: only the averaged result is compared";
  r.writeReg(DIAG_ALRT, 0);  // raw comparisons from now on, same analog inputs
  r.advance(fromUs(200));
  EXPECT_TRUE(r.readReg(DIAG_ALRT, 2) & POL);
}

TEST(Ina228Model, OnlyMeasuredChannelsFlagAndLimitWritesApplyAtOnce) {
  Rig r;
  r.writeReg(SOVL, 10);                 // 50 uV
  r.writeReg(ADC_CONFIG, (0x9 << 12));  // bus only, 50 us: the shunt is not measured
  r.chip.setAnalog({0.001, 12.0, 25.0});
  r.advance(fromUs(200));
  EXPECT_FALSE(r.readReg(DIAG_ALRT, 2) & SHNTOL);
  r.writeReg(ADC_CONFIG, (0xB << 12));  // bus + shunt
  r.advance(fromUs(200));
  EXPECT_TRUE(r.readReg(DIAG_ALRT, 2) & SHNTOL);
  r.writeReg(SOVL, 0x7FFF);  // limit raised: transparent flag follows at the next sample
  r.advance(fromUs(200));
  EXPECT_FALSE(r.readReg(DIAG_ALRT, 2) & SHNTOL);
  r.writeReg(BUVL, std::uint16_t(13.0 / 3.125e-3));  // 13 V: the bus reads under
  r.advance(fromUs(200));
  EXPECT_TRUE(r.readReg(DIAG_ALRT, 2) & BUSUL);
  r.writeReg(BUVL, 0);
  r.advance(fromUs(200));
  EXPECT_FALSE(r.readReg(DIAG_ALRT, 2) & BUSUL);
}

}  // namespace
}  // namespace xr::sim
