// ADS1115 model against docs/sources.md, datasheet facts §2.
#include "drivers/sim/ads1115_model.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <cmath>
#include <limits>

#include "drivers/sim/sim_i2c_bus.h"

namespace xr::sim {
namespace {

struct Rig {
  TimeNs now = 0;
  SimI2cBus bus{&now};
  Ads1115Model chip;
  explicit Rig(double clock = 1.0) : chip(clock) { bus.attach(0x48, &chip); }
  int writeReg(std::uint8_t reg, std::uint16_t v) {
    std::uint8_t b[3] = {reg, std::uint8_t(v >> 8), std::uint8_t(v)};
    I2cMsg m{0x48, false, b, 3};
    return bus.transfer({&m, 1});
  }
  std::uint16_t readReg(std::uint8_t reg, int* rc = nullptr) {
    std::uint8_t p = reg, buf[2] = {};
    I2cMsg m[2] = {{0x48, false, &p, 1}, {0x48, true, buf, 2}};
    const int r = bus.transfer(m);
    if (rc) *rc = r;
    return std::uint16_t((buf[0] << 8) | buf[1]);
  }
  void advance(TimeNs dt) {
    now += dt;
    chip.update(now);
  }
};

// Config: OS | MUX | PGA | MODE | DR | COMP_QUE=11
std::uint16_t cfg(int os, int mux, int pga, int single, int dr, int que = 3) {
  return std::uint16_t((os << 15) | (mux << 12) | (pga << 9) | (single << 8) | (dr << 5) | que);
}

TEST(Ads1115Model, ResetValues) {
  Rig r;
  EXPECT_EQ(r.readReg(1), 0x8583);
  EXPECT_EQ(r.readReg(0), 0x0000);
  EXPECT_EQ(r.readReg(2), 0x8000);
  EXPECT_EQ(r.readReg(3), 0x7FFF);
}

TEST(Ads1115Model, SingleShotTakesOneDataPeriodAndOsReportsBusy) {
  Rig r;
  r.chip.setInputs({1.0, 0, 0, 0});
  ASSERT_EQ(r.writeReg(1, cfg(1, 4, 1, 1, 4)), 0);  // AIN0-GND, ±4.096 V, 128 SPS
  EXPECT_EQ(r.readReg(1) & 0x8000, 0);              // converting
  r.advance(fromSec(1.0 / 128) - 1000);
  EXPECT_EQ(r.readReg(1) & 0x8000, 0);
  EXPECT_EQ(r.readReg(0), 0);
  r.advance(1000);
  EXPECT_EQ(r.readReg(1) & 0x8000, 0x8000);
  EXPECT_EQ(r.readReg(0), 8000);  // 1 V / 125 uV
  // Powered down: no further conversions.
  r.chip.setInputs({2.0, 0, 0, 0});
  r.advance(fromMs(100));
  EXPECT_EQ(r.readReg(0), 8000);
  EXPECT_EQ(r.chip.conversions(), 1u);
}

TEST(Ads1115Model, ConversionTimePerDataRate) {
  for (int dr = 0; dr < 8; ++dr) {
    Rig r;
    r.writeReg(1, cfg(1, 4, 1, 1, dr));
    const TimeNs p = TimeNs(1e9 / ads1115::kDataRateSps[dr]);
    r.advance(p - 2);
    EXPECT_EQ(r.chip.conversions(), 0u) << dr;
    r.advance(2);
    EXPECT_EQ(r.chip.conversions(), 1u) << dr;
  }
}

TEST(Ads1115Model, SlowOscillatorStretchesConversions) {
  Rig r(1.1);
  r.writeReg(1, cfg(1, 4, 1, 1, 7));
  r.advance(TimeNs(1e9 / 860));
  EXPECT_EQ(r.chip.conversions(), 0u);
  r.advance(TimeNs(0.1e9 / 860) + 10);
  EXPECT_EQ(r.chip.conversions(), 1u);
}

TEST(Ads1115Model, OsWriteIgnoredWhileBusy) {
  Rig r;
  r.writeReg(1, cfg(1, 4, 1, 1, 0));  // 8 SPS: 125 ms
  r.advance(fromMs(100));
  r.writeReg(1, cfg(1, 4, 1, 1, 0));
  r.advance(fromMs(30));
  EXPECT_EQ(r.chip.conversions(), 1u);  // the first finished at 125 ms, no restart
  EXPECT_FALSE(r.chip.converting());
}

TEST(Ads1115Model, ContinuousConfigChangeAppliesAfterConversionInProgress) {
  Rig r;
  r.chip.setInputs({1.0, 2.0, 0, 0});
  r.writeReg(1, cfg(0, 4, 1, 0, 4));  // continuous AIN0
  const TimeNs p = TimeNs(1e9 / 128);
  r.advance(p / 2);
  r.writeReg(1, cfg(0, 5, 1, 0, 4));  // switch to AIN1 mid-conversion
  r.advance(p / 2 + 1);
  EXPECT_EQ(std::int16_t(r.readReg(0)), 8000);  // still the old channel
  r.advance(p);
  EXPECT_EQ(std::int16_t(r.readReg(0)), 16000);  // the new one
  EXPECT_TRUE(r.chip.converting());
}

TEST(Ads1115Model, ClipsAtFullScaleCodes) {
  Rig r;
  r.chip.setInputs({3.0, 0, 0, 0});
  r.writeReg(1, cfg(1, 4, 2, 1, 7));  // ±2.048 V
  r.advance(fromMs(2));
  EXPECT_EQ(r.readReg(0), 0x7FFF);
  r.chip.setInputs({0.0, 3.0, 0, 0});
  r.writeReg(1, cfg(1, 0, 2, 1, 7));  // AIN0-AIN1 = -3 V
  r.advance(fromMs(2));
  EXPECT_EQ(r.readReg(0), 0x8000);
}

TEST(Ads1115Model, DifferentialAndPgaScaling) {
  Rig r;
  r.chip.setInputs({0.3, 0.1, 0, 0});
  r.writeReg(1, cfg(1, 0, 5, 1, 7));  // ±0.256 V: 7.8125 uV/LSB
  r.advance(fromMs(2));
  EXPECT_EQ(std::int16_t(r.readReg(0)), 25600);
}

TEST(Ads1115Model, RejectsBadPointerAndConversionWrite) {
  Rig r;
  std::uint8_t b[1] = {0x04};
  I2cMsg m{0x48, false, b, 1};
  EXPECT_EQ(r.bus.transfer({&m, 1}), EREMOTEIO);
  EXPECT_EQ(r.writeReg(0, 0x1234), EREMOTEIO);
  EXPECT_EQ(r.chip.protocolErrors(), 2u);
}

TEST(Ads1115Model, AlertRdyAsConversionReadySingleShot) {
  Rig r;
  r.writeReg(3, 0x8000);  // Hi MSB = 1
  r.writeReg(2, 0x0000);  // Lo MSB = 0
  r.writeReg(1, cfg(1, 4, 1, 1, 7, 0));
  EXPECT_FALSE(r.chip.alertActive());
  r.advance(fromMs(2));
  EXPECT_TRUE(r.chip.alertActive());
  r.writeReg(1, cfg(1, 4, 1, 1, 7, 0));  // next start: pin follows OS (busy)
  EXPECT_FALSE(r.chip.alertActive());
}

TEST(Ads1115Model, AlertRdyPulsesInContinuous) {
  Rig r;
  r.writeReg(3, 0x8000);
  r.writeReg(2, 0x0000);
  r.writeReg(1, cfg(0, 4, 1, 0, 4, 0));
  r.advance(fromMs(100));
  EXPECT_EQ(r.chip.readyPulses(), 12u);  // 100 ms / 7.8125 ms
}

TEST(Ads1115Model, ThresholdWritesSwitchBetweenReadyPinAndComparator) {
  Rig r;
  r.writeReg(1, cfg(0, 4, 1, 0, 4, 0));  // continuous, 128 SPS, queue 1
  r.advance(fromMs(20));
  EXPECT_EQ(r.chip.nextReadyEdge(), -1) << "reset thresholds: comparator, no ready pulses";
  r.writeReg(3, 0x8000);
  EXPECT_EQ(r.chip.nextReadyEdge(), -1) << "Lo_thresh MSB still 1";
  r.writeReg(2, 0x0000);
  EXPECT_GT(r.chip.nextReadyEdge(), r.now);
  r.advance(fromMs(40));
  const auto pulses = r.chip.readyPulses();
  EXPECT_EQ(pulses, 5u);  // 40 ms / 7.8125 ms
  r.writeReg(3, 0x7FFF);  // Hi_thresh MSB back to 0: comparator again
  EXPECT_EQ(r.chip.nextReadyEdge(), -1);
  r.advance(fromMs(40));
  EXPECT_EQ(r.chip.readyPulses(), pulses);
  r.writeReg(3, 0x8000);
  r.writeReg(2, 0x8000);  // Lo_thresh MSB 1: not the ready pin either
  EXPECT_EQ(r.chip.nextReadyEdge(), -1);
  r.writeReg(2, 0x0001);
  EXPECT_GT(r.chip.nextReadyEdge(), r.now);
}

TEST(Ads1115Model, TraditionalComparatorWithQueue) {
  Rig r;
  r.writeReg(3, 8000);                   // hi
  r.writeReg(2, 4000);                   // lo
  r.chip.setInputs({1.5, 0, 0, 0});      // 12000 codes at ±4.096
  r.writeReg(1, cfg(0, 4, 1, 0, 7, 1));  // continuous, assert after 2
  r.advance(TimeNs(1e9 / 860) + 10);
  EXPECT_FALSE(r.chip.alertActive());
  r.advance(TimeNs(1e9 / 860));
  EXPECT_TRUE(r.chip.alertActive());
  r.chip.setInputs({0.75, 0, 0, 0});  // 6000: between lo and hi, stays (hysteresis)
  r.advance(fromMs(5));
  EXPECT_TRUE(r.chip.alertActive());
  r.chip.setInputs({0.25, 0, 0, 0});  // below lo: releases
  r.advance(fromMs(5));
  EXPECT_FALSE(r.chip.alertActive());
}

}  // namespace
}  // namespace xr::sim

namespace xr::sim {
namespace {

TEST(Ads1115Model, WindowComparatorLatchesUntilConversionRead) {
  Rig r;
  r.writeReg(3, 8000);
  r.writeReg(2, 4000);
  r.chip.setInputs({0.25, 0, 0, 0});                       // 2000: below the window
  r.writeReg(1, cfg(0, 4, 1, 0, 7, 0) | 0x0010 | 0x0004);  // window, latching, assert after 1
  r.advance(fromMs(2));
  EXPECT_TRUE(r.chip.alertActive());
  r.chip.setInputs({0.75, 0, 0, 0});  // back inside: latched, stays
  r.advance(fromMs(5));
  EXPECT_TRUE(r.chip.alertActive());
  r.readReg(0);  // reading the conversion clears the latch
  EXPECT_FALSE(r.chip.alertActive());
  r.advance(fromMs(5));
  EXPECT_FALSE(r.chip.alertActive());
}

TEST(Ads1115Model, SwitchingToSingleShotStopsAfterCurrentConversion) {
  Rig r;
  r.writeReg(1, cfg(0, 4, 1, 0, 7));
  r.advance(fromMs(10));
  const auto n = r.chip.conversions();
  EXPECT_GE(n, 8u);
  r.writeReg(1, cfg(0, 4, 1, 1, 7));  // MODE=1 without OS
  r.advance(fromMs(10));
  EXPECT_LE(r.chip.conversions(), n + 1);
  EXPECT_FALSE(r.chip.converting());
}

}  // namespace
}  // namespace xr::sim

namespace xr::sim {
namespace {

// A conversion samples its pins (and draws their noise) at the instant it
// ends: only the pins its MUX selects, once per conversion. Counted by the
// noise draws against a reference generator (one draw per sampled pin with
// a sigma > 0); a sigma of 1 nV leaves the codes exact.
bool inStep(const Rng& a, const Rng& b) {
  Rng x = a, y = b;
  return x.next() == y.next();
}

TEST(Ads1115Model, PinsAreSampledOnlyForTheMuxPinsAtEachConversion) {
  Rig r;
  Rng rng(7), ref(7);
  constexpr double kSigma = 1e-9;
  r.chip.setInputs({0.5, 0.25, 1.0, 0.125});
  r.chip.setInputNoise(&rng, {kSigma, kSigma, kSigma, kSigma}, 5.3);
  ASSERT_EQ(r.writeReg(1, cfg(1, 6, 1, 1, 7)), 0);  // AIN2-GND, ±4.096 V, single-shot 860 SPS
  EXPECT_TRUE(inStep(rng, ref)) << "nothing sampled before the conversion ends";
  r.advance(fromMs(2));
  (void)ref.gauss(kSigma);  // AIN2 only
  EXPECT_TRUE(inStep(rng, ref));
  EXPECT_EQ(r.readReg(0), 8000);                    // 1 V / 125 uV
  ASSERT_EQ(r.writeReg(1, cfg(1, 0, 1, 1, 7)), 0);  // AIN0-AIN1 differential
  r.advance(fromMs(2));
  (void)ref.gauss(kSigma);  // AIN0
  (void)ref.gauss(kSigma);  // AIN1
  EXPECT_TRUE(inStep(rng, ref));
  EXPECT_EQ(r.readReg(0), 2000);  // 0.25 V
  // Continuous: one sample per conversion.
  const std::uint64_t before = r.chip.conversions();
  ASSERT_EQ(r.writeReg(1, cfg(0, 7, 1, 0, 7)), 0);  // AIN3-GND continuous
  r.advance(fromMs(100));
  const std::uint64_t n = r.chip.conversions() - before;
  EXPECT_GT(n, 80u);
  for (std::uint64_t i = 0; i < n; ++i) (void)ref.gauss(kSigma);
  EXPECT_TRUE(inStep(rng, ref));
  EXPECT_EQ(r.readReg(0), 1000);  // 0.125 V
  // Without a generator the set values are read as they are, with no draws.
  r.chip.setInputNoise(nullptr, {}, 0.0);
  r.chip.setInputs({3.0, 3.0, 3.0, 3.0});
  r.advance(fromMs(5));
  EXPECT_TRUE(inStep(rng, ref));
  EXPECT_EQ(r.readReg(0), 24000);  // 3 V
}

TEST(Ads1115Model, InputNoiseIsDrawnForTheSampledPinOnlyAndClamped) {
  Rig r;
  Rng rng(42), ref(42);
  r.chip.setInputs({1.0, 2.0, 9.0, -1.0});
  r.chip.setInputNoise(&rng, {0.01, 0.0, 0.02, 0.0}, 5.3);
  // AIN0-GND single-shot, ±4.096 V: one draw, the one a reference generator gives.
  ASSERT_EQ(r.writeReg(1, cfg(1, 4, 1, 1, 7)), 0);
  r.advance(fromMs(2));
  const double v0 = 1.0 + ref.gauss(0.01);
  EXPECT_EQ(std::int16_t(r.readReg(0)), std::int16_t(std::nearbyint(v0 / 4.096 * 32768.0)));
  // AIN1 has sigma 0: no draw at all (the generators stay in step).
  ASSERT_EQ(r.writeReg(1, cfg(1, 5, 1, 1, 7)), 0);
  r.advance(fromMs(2));
  EXPECT_EQ(r.readReg(0), 16000);  // 2 V exactly
  // AIN2 draws, then clamps at vmax (±6.144 V range so 5.3 V is on scale).
  ASSERT_EQ(r.writeReg(1, cfg(1, 6, 0, 1, 7)), 0);
  r.advance(fromMs(2));
  (void)ref.gauss(0.02);
  EXPECT_EQ(std::int16_t(r.readReg(0)), std::int16_t(std::nearbyint(5.3 / 6.144 * 32768.0)));
  // AIN3 below ground reads 0 V; a differential AIN0-AIN3 samples AIN0 (one draw) then AIN3.
  ASSERT_EQ(r.writeReg(1, cfg(1, 7, 1, 1, 7)), 0);
  r.advance(fromMs(2));
  EXPECT_EQ(r.readReg(0), 0);
  ASSERT_EQ(r.writeReg(1, cfg(1, 1, 1, 1, 7)), 0);
  r.advance(fromMs(2));
  const double d = 1.0 + ref.gauss(0.01);
  EXPECT_EQ(std::int16_t(r.readReg(0)), std::int16_t(std::nearbyint(d / 4.096 * 32768.0)));
  EXPECT_EQ(rng.next(), ref.next()) << "exactly the draws of the sampled pins";
  // A non-finite pin voltage reads 0 V, +inf included (not the clamp value).
  r.chip.setInputs({std::numeric_limits<double>::infinity(), std::nan(""), 0, 0});
  r.chip.setInputSigma(0, 0.0);
  ASSERT_EQ(r.writeReg(1, cfg(1, 4, 1, 1, 7)), 0);
  r.advance(fromMs(2));
  EXPECT_EQ(r.readReg(0), 0);
  ASSERT_EQ(r.writeReg(1, cfg(1, 5, 1, 1, 7)), 0);
  r.advance(fromMs(2));
  EXPECT_EQ(r.readReg(0), 0);
}

// The ready-edge transaction (pointer 0, 2-byte read, Config write) has a
// fast path in transact(): it must leave the chip exactly as the same
// messages sent one by one, and a third message that is not a Config write
// must still be handled (and refused) as such.
TEST(Ads1115Model, EdgeTransactionMatchesMessagesOneByOne) {
  Rig a, b;
  for (Rig* r : {&a, &b}) {
    r->chip.setInputs({1.0, 2.0, 0.5, 3.0});
    r->writeReg(3, 0x8000);
    r->writeReg(2, 0x0000);
    r->writeReg(1, cfg(0, 4, 1, 0, 7, 0));  // continuous, AIN0, ready pulses
  }
  for (int i = 0; i < 8; ++i) {
    const std::uint16_t next = cfg(0, 4 + (i % 4), 1, 0, 7, 0);
    a.advance(a.chip.period(7));
    b.advance(b.chip.period(7));
    std::uint8_t ptrA = 0, rxA[2] = {}, wrA[3] = {1, std::uint8_t(next >> 8), std::uint8_t(next)};
    I2cMsg ma[3] = {{0x48, false, &ptrA, 1}, {0x48, true, rxA, 2}, {0x48, false, wrA, 3}};
    ASSERT_EQ(a.bus.transfer(ma), 0);
    std::uint8_t ptrB = 0, rxB[2] = {}, wrB[3] = {1, std::uint8_t(next >> 8), std::uint8_t(next)};
    I2cMsg mb[3] = {{0x48, false, &ptrB, 1}, {0x48, true, rxB, 2}, {0x48, false, wrB, 3}};
    for (I2cMsg& m : mb) ASSERT_EQ(b.bus.transfer({&m, 1}), 0);
    EXPECT_EQ(rxA[0], rxB[0]);
    EXPECT_EQ(rxA[1], rxB[1]);
    EXPECT_EQ(a.chip.peekConfig(), b.chip.peekConfig());
    EXPECT_EQ(a.chip.nextReadyEdge(), b.chip.nextReadyEdge());
    EXPECT_EQ(a.chip.alertActive(), b.chip.alertActive());
    // The retained pointer: a read without a pointer write.
    std::uint8_t pa[2] = {}, pb[2] = {};
    I2cMsg ra{0x48, true, pa, 2}, rb{0x48, true, pb, 2};
    ASSERT_EQ(a.bus.transfer({&ra, 1}), 0);
    ASSERT_EQ(b.bus.transfer({&rb, 1}), 0);
    EXPECT_EQ(pa[0], pb[0]);
    EXPECT_EQ(pa[1], pb[1]);
  }
  EXPECT_NE(a.chip.peekConversion(), 0);
  // Pointer 0, read, then a write to the read-only Conversion register: the
  // read happens, the write is refused, the pointer stays at 0.
  std::uint8_t ptr = 0, rx[2] = {}, bad[3] = {0, 0x12, 0x34};
  I2cMsg m[3] = {{0x48, false, &ptr, 1}, {0x48, true, rx, 2}, {0x48, false, bad, 3}};
  const std::uint64_t errors = a.chip.protocolErrors();
  EXPECT_EQ(a.bus.transfer(m), EREMOTEIO);
  EXPECT_EQ(std::uint16_t((rx[0] << 8) | rx[1]), std::uint16_t(a.chip.peekConversion()));
  EXPECT_EQ(a.chip.protocolErrors(), errors + 1);
  // A threshold write as the third message takes effect as one: Lo_thresh
  // MSB = 1 ends the conversion-ready function, so the pin stops pulsing.
  std::uint8_t lo[3] = {2, 0x81, 0x00};
  I2cMsg m2[3] = {{0x48, false, &ptr, 1}, {0x48, true, rx, 2}, {0x48, false, lo, 3}};
  EXPECT_EQ(a.bus.transfer(m2), 0);
  EXPECT_EQ(a.readReg(2), 0x8100);
  EXPECT_EQ(a.chip.nextReadyEdge(), -1);
}

}  // namespace
}  // namespace xr::sim
