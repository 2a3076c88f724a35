// Ina228Driver against the simulator's INA228 model (drivers/sim), written
// separately from the same datasheet facts: detection, configuration,
// readings, fast/slow mode, BOVL and the ALERT, NACKs and hot-plug.
#include "drivers/ina228/ina228_driver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>

#include "drivers/ina228/ina228_registers.h"
#include "drivers/sim/ina228_model.h"
#include "sim_fixture.h"

namespace xr {
namespace {

constexpr std::uint16_t kAddr = 0x40;

class Ina228DriverTest : public ::testing::Test {
 protected:
  Ina228DriverTest() : bus(&t.now), drv(bus, kAddr, 0.0005, 200.0) {
    bus.attach(kAddr, &chip);
    setPins(13.2, 50.0);
  }
  void setPins(double vbus, double amps) { chip.setAnalog({amps * 0.0005, vbus, 31.0}); }
  // Advance virtual time and poll every `step` until `until`.
  const Ina228Sample& runFor(TimeNs dur, TimeNs step = 2'500'000) {
    const TimeNs end = t.now + dur;
    while (t.now < end) {
      t.now += step;
      drv.poll(t.now);
    }
    return drv.sample();
  }
  test::VirtualTime t;
  sim::SimI2cBus bus;
  sim::Ina228Model chip;
  Ina228Driver drv;
};

TEST_F(Ina228DriverTest, DetectsByManufacturerAndDeviceId) { EXPECT_EQ(drv.detect(), 0); }

TEST_F(Ina228DriverTest, AbsentChipIsABusErrorNotAMatch) {
  bus.detach(kAddr);
  EXPECT_NE(drv.detect(), 0);
  EXPECT_NE(drv.start(t.now), 0);
  EXPECT_FALSE(drv.present());
}

TEST_F(Ina228DriverTest, ConfigureProgramsCalibrationAlertAndLimit) {
  ASSERT_EQ(drv.setBusOvervoltageLimit(14.8), 0);
  ASSERT_EQ(drv.start(t.now), 0);
  EXPECT_TRUE(drv.present());
  EXPECT_EQ(chip.peek(sim::ina228::SHUNT_CAL), 2500u);
  EXPECT_EQ(chip.peek(sim::ina228::CONFIG) & (1u << 4), 0u) << "ADCRANGE 0 for a 100 mV full-scale shunt";
  EXPECT_EQ(chip.peek(sim::ina228::BOVL), ina228::bovlCode(14.8));
  const auto diag = chip.peek(sim::ina228::DIAG_ALRT);
  EXPECT_TRUE(diag & sim::ina228::SLOWALERT);
  EXPECT_FALSE(diag & sim::ina228::APOL) << "ALERT active low";
  EXPECT_FALSE(diag & sim::ina228::ALATCH);
  EXPECT_EQ(chip.peek(sim::ina228::ADC_CONFIG), ina228::kAdcConfigSlow);
  EXPECT_EQ(chip.protocolErrors(), 0u);
}

TEST_F(Ina228DriverTest, ReadsBusVoltageCurrentAndDieTemperature) {
  ASSERT_EQ(drv.start(t.now), 0);
  const auto& s = runFor(3'000'000'000);
  EXPECT_NEAR(s.busVolts, 13.2, 0.002);
  EXPECT_NEAR(s.currentA, 50.0, 0.05);
  EXPECT_NEAR(s.dieTempC, 31.0, 0.05);
  EXPECT_GT(s.stamp, 0);
  EXPECT_EQ(chip.protocolErrors(), 0u);
}

TEST_F(Ina228DriverTest, FreshChipIsNotReadBeforeItsFirstConversion) {
  // A just-configured INA228 still holds its reset VBUS of 0 V: reading it
  // would look like a dead sensor (critical disagreement) at every start.
  ASSERT_EQ(drv.start(t.now), 0);
  const auto& first = drv.poll(t.now);
  EXPECT_FALSE(first.fresh);
  EXPECT_EQ(first.stamp, 0);
  const auto& later = runFor(drv.conversionCycle() + 5'000'000);
  EXPECT_GT(later.stamp, 0);
  EXPECT_NEAR(later.busVolts, 13.2, 0.002);
}

TEST_F(Ina228DriverTest, ModeChangeWaitsForTheNewModesFirstResult) {
  ASSERT_EQ(drv.start(t.now), 0);
  runFor(3'000'000'000);
  const TimeNs before = drv.sample().stamp;
  ASSERT_EQ(drv.setFastMode(true), 0);
  t.now += 1'000'000;  // 1 ms: shorter than one fast conversion cycle
  EXPECT_FALSE(drv.poll(t.now).fresh);
  EXPECT_EQ(drv.sample().stamp, before);
  const auto& s = runFor(drv.conversionCycle() + 2'500'000, 500'000);
  EXPECT_GT(s.stamp, before);
}

TEST_F(Ina228DriverTest, NegativeCurrentAndInversion) {
  setPins(12.6, -30.0);
  ASSERT_EQ(drv.start(t.now), 0);
  EXPECT_NEAR(runFor(3'000'000'000).currentA, -30.0, 0.05);
  Ina228Driver inv(bus, kAddr, 0.0005, 200.0, /*invertCurrent=*/true);
  ASSERT_EQ(inv.start(t.now), 0);
  const TimeNs end = t.now + 3'000'000'000;
  while (t.now < end) inv.poll(t.now += 2'500'000);
  EXPECT_NEAR(inv.sample().currentA, 30.0, 0.05);
}

TEST_F(Ina228DriverTest, FastModeWhileFieldOnChangesTheChipCadence) {
  ASSERT_EQ(drv.start(t.now), 0);
  EXPECT_FALSE(drv.fastModeActive());
  ASSERT_EQ(drv.setFastMode(true), 0);
  EXPECT_TRUE(drv.fastModeActive());
  EXPECT_EQ(chip.peek(sim::ina228::ADC_CONFIG), ina228::kAdcConfigFast);
  EXPECT_EQ(chip.updatePeriod(), drv.conversionCycle());
  EXPECT_LT(drv.conversionCycle(), 5'000'000);
  // A step in current shows up within a few fast cycles.
  runFor(50'000'000);
  setPins(13.2, 80.0);
  EXPECT_NEAR(runFor(20'000'000).currentA, 80.0, 0.1);
  ASSERT_EQ(drv.setFastMode(false), 0);
  EXPECT_EQ(chip.peek(sim::ina228::ADC_CONFIG), ina228::kAdcConfigSlow);
  EXPECT_GT(drv.conversionCycle(), 1'000'000'000);
}

TEST_F(Ina228DriverTest, FreshOnlyWhenANewResultIsDue) {
  ASSERT_EQ(drv.start(t.now), 0);
  drv.setFastMode(true);
  int fresh = 0, polls = 0;
  for (int i = 0; i < 400; ++i) {  // one second of 2.5 ms ticks
    t.now += 2'500'000;
    fresh += drv.poll(t.now).fresh ? 1 : 0;
    ++polls;
  }
  // ~4.5 ms cycle -> about every second tick; never every tick.
  EXPECT_GT(fresh, 150);
  EXPECT_LT(fresh, 250);
}

TEST_F(Ina228DriverTest, BusOvervoltageFlagAndAlertAboveBovl) {
  ASSERT_EQ(drv.start(t.now), 0);
  drv.setFastMode(true);
  ASSERT_EQ(drv.setBusOvervoltageLimit(14.8), 0);
  setPins(14.7, 10.0);
  EXPECT_FALSE(runFor(50'000'000).busOvervoltage);
  EXPECT_FALSE(chip.alertActive());
  setPins(14.9, 10.0);
  EXPECT_TRUE(runFor(50'000'000).busOvervoltage);
  EXPECT_TRUE(chip.alertActive());
  EXPECT_FALSE(chip.alertPinHigh()) << "active low";
  // A BulkVoltage change moves the limit: 15.1 V now clears it.
  ASSERT_EQ(drv.setBusOvervoltageLimit(15.1), 0);
  EXPECT_FALSE(runFor(50'000'000).busOvervoltage);
}

TEST_F(Ina228DriverTest, RunOfNacksMarksAbsentThenRedetectsRateLimited) {
  ASSERT_EQ(drv.setBusOvervoltageLimit(14.8), 0);
  ASSERT_EQ(drv.start(t.now), 0);
  drv.setFastMode(true);
  runFor(20'000'000);
  bus.setNack(kAddr, true);
  for (unsigned i = 0; i < Ina228Driver::kFailRunForRedetect - 1; ++i) drv.poll(t.now += 2'500'000);
  EXPECT_TRUE(drv.present()) << "a short run of failures is tolerated";
  drv.poll(t.now += 2'500'000);
  EXPECT_FALSE(drv.present());
  EXPECT_GE(drv.stats().failedReads, Ina228Driver::kFailRunForRedetect);
  EXPECT_NE(drv.stats().lastError, 0);
  // Chip back, but re-detection waits for the rate limit.
  bus.setNack(kAddr, false);
  const auto transfersBefore = bus.transfers();
  drv.poll(t.now += 2'500'000);
  EXPECT_FALSE(drv.present());
  EXPECT_EQ(bus.transfers(), transfersBefore) << "no bus traffic while waiting to re-detect";
  runFor(Ina228Driver::kRedetectInterval);
  EXPECT_TRUE(drv.present());
  EXPECT_EQ(drv.stats().redetects, 1u);
}

TEST_F(Ina228DriverTest, HotPlugOfAFreshChipGetsFullyReprogrammed) {
  ASSERT_EQ(drv.setBusOvervoltageLimit(14.8), 0);
  ASSERT_EQ(drv.start(t.now), 0);
  drv.setFastMode(true);
  runFor(20'000'000);
  bus.detach(kAddr);  // unplugged
  runFor(100'000'000);
  EXPECT_FALSE(drv.present());
  sim::Ina228Model fresh;  // a new chip with reset registers
  fresh.setAnalog({20.0 * 0.0005, 13.0, 25.0});
  bus.attach(kAddr, &fresh);
  runFor(2'000'000'000);
  ASSERT_TRUE(drv.present());
  EXPECT_EQ(fresh.peek(sim::ina228::BOVL), ina228::bovlCode(14.8));
  EXPECT_EQ(fresh.peek(sim::ina228::SHUNT_CAL), 2500u);
  EXPECT_EQ(fresh.peek(sim::ina228::ADC_CONFIG), ina228::kAdcConfigFast);
  EXPECT_NEAR(drv.sample().currentA, 20.0, 0.05);
  EXPECT_EQ(fresh.protocolErrors(), 0u);
}

TEST_F(Ina228DriverTest, SilentChipResetIsRepairedByTheReadBack) {
  // A brown-out resets the chip without any failed read: BOVL back at
  // 0x7FFF would disable the hardware OV backup.
  ASSERT_EQ(drv.setBusOvervoltageLimit(14.8), 0);
  ASSERT_EQ(drv.start(t.now), 0);
  runFor(100'000'000);
  sim::Ina228Model reset;
  reset.setAnalog({10.0 * 0.0005, 13.0, 25.0});
  bus.attach(kAddr, &reset);
  runFor(Ina228Driver::kHousekeepingInterval + 10'000'000);
  EXPECT_GE(drv.stats().reconfigures, 1u);
  EXPECT_EQ(reset.peek(sim::ina228::BOVL), ina228::bovlCode(14.8));
  EXPECT_EQ(reset.peek(sim::ina228::SHUNT_CAL), 2500u);
}

// A chip at the address that is not an INA228.
class OtherChip final : public sim::SimI2cDevice {
 public:
  void update(TimeNs) noexcept override {}
  int write(const std::uint8_t* buf, std::size_t len) noexcept override {
    if (len >= 1) ptr_ = buf[0];
    return 0;
  }
  int read(std::uint8_t* buf, std::size_t len) noexcept override {
    for (std::size_t i = 0; i < len; ++i) buf[i] = static_cast<std::uint8_t>(0x12 + ptr_);
    return 0;
  }

 private:
  std::uint8_t ptr_ = 0;
};

TEST_F(Ina228DriverTest, WrongIdsAreEnodev) {
  OtherChip other;
  bus.attach(kAddr, &other);
  EXPECT_EQ(drv.detect(), ENODEV);
  EXPECT_EQ(drv.start(t.now), ENODEV);
  EXPECT_FALSE(drv.present());
}

TEST_F(Ina228DriverTest, UnencodableShuntIsRejected) {
  Ina228Driver bad(bus, kAddr, 0.0, 200.0);
  EXPECT_EQ(bad.start(t.now), EINVAL);
  EXPECT_FALSE(bad.present());
  EXPECT_EQ(drv.setBusOvervoltageLimit(-3.0), EINVAL);
}

}  // namespace
}  // namespace xr

#include "drivers/ina228/ina228_inputs.h"

namespace xr {
namespace {

TEST_F(Ina228DriverTest, FillsTheCoreInputs) {
  ASSERT_EQ(drv.start(t.now), 0);
  drv.setFastMode(true);
  Inputs in;
  bool sawFresh = false;
  for (int i = 0; i < 40; ++i) {
    drv.poll(t.now += 2'500'000);
    fillInaInputs(drv, in);
    sawFresh = sawFresh || in.IBV.fresh;
  }
  EXPECT_TRUE(sawFresh);
  EXPECT_TRUE(in.inaPresent);
  EXPECT_TRUE(in.inaFastModeActive);
  EXPECT_NEAR(in.IBV.value, 13.2, 0.002);
  EXPECT_NEAR(in.Bcur.value, 50.0, 0.05);
  EXPECT_GT(in.IBV.stamp, 0);
  EXPECT_GT(in.inaDiagStamp, 0);
  bus.setNack(kAddr, true);
  for (int i = 0; i < 10; ++i) drv.poll(t.now += 2'500'000);
  fillInaInputs(drv, in);
  EXPECT_FALSE(in.inaPresent);
  EXPECT_FALSE(in.IBV.fresh);
}

}  // namespace
}  // namespace xr

namespace xr {
namespace {

TEST_F(Ina228DriverTest, FailedModeWriteReportsTheModeTheChipIsIn) {
  ASSERT_EQ(drv.start(t.now), 0);
  bus.setNack(kAddr, true);
  EXPECT_NE(drv.setFastMode(true), 0);
  EXPECT_FALSE(drv.fastModeActive()) << "the chip is still in slow mode";
  bus.setNack(kAddr, false);
  EXPECT_EQ(drv.setFastMode(true), 0);
  EXPECT_TRUE(drv.fastModeActive());
  EXPECT_EQ(chip.peek(sim::ina228::ADC_CONFIG), ina228::kAdcConfigFast);
}

TEST_F(Ina228DriverTest, ModeAndLimitChosenWhileAbsentAreAppliedOnDetection) {
  bus.detach(kAddr);
  EXPECT_NE(drv.start(t.now), 0);
  EXPECT_EQ(drv.setFastMode(true), 0);
  EXPECT_EQ(drv.setBusOvervoltageLimit(29.1), 0);
  bus.attach(kAddr, &chip);
  runFor(Ina228Driver::kRedetectInterval + 10'000'000);
  ASSERT_TRUE(drv.present());
  EXPECT_EQ(chip.peek(sim::ina228::ADC_CONFIG), ina228::kAdcConfigFast);
  EXPECT_EQ(chip.peek(sim::ina228::BOVL), ina228::bovlCode(29.1));
}

}  // namespace
}  // namespace xr

namespace xr {
namespace {

TEST_F(Ina228DriverTest, AtMostTwoTransfersInAnySteadyStateTick) {
  // Bounded bus time per control tick: DIAG_ALRT (+ VBUS, CURRENT when due)
  // in one combined transaction, and at most one housekeeping register.
  ASSERT_EQ(drv.setBusOvervoltageLimit(14.8), 0);
  ASSERT_EQ(drv.start(t.now), 0);
  drv.setFastMode(true);
  std::uint64_t worst = 0;
  for (int i = 0; i < 2000; ++i) {
    const auto before = bus.transfers();
    drv.poll(t.now += 2'500'000);
    worst = std::max<std::uint64_t>(worst, bus.transfers() - before);
  }
  EXPECT_EQ(worst, 2u);
  EXPECT_EQ(drv.stats().reconfigures, 0u) << "a healthy chip is never reconfigured";
}

TEST_F(Ina228DriverTest, OneCombinedTransactionPerTickInRegisterOrder) {
  // DIAG_ALRT every tick, VBUS and CURRENT when a result is due: the same
  // register reads in the same order as separate transfers, in one
  // transaction (one I2C_RDWR ioctl on the board).
  test::RecordingBus rec(bus);
  Ina228Driver d(rec, kAddr, 0.0005, 200.0);
  ASSERT_EQ(d.start(t.now), 0);
  d.setFastMode(true);
  for (int i = 0; i < 400; ++i) d.poll(t.now += 2'500'000);  // past the housekeeping round
  int withResult = 0, diagOnly = 0;
  for (int i = 0; i < 40; ++i) {
    rec.clear();
    const bool fresh = d.poll(t.now += 2'500'000).fresh;
    // One transaction per tick, plus one housekeeping read on 4 ticks a second.
    ASSERT_GE(rec.sizes().size(), 1u);
    ASSERT_LE(rec.sizes().size(), 2u);
    const auto& m = rec.log();
    ASSERT_EQ(rec.sizes()[0], fresh ? 6u : 2u);
    EXPECT_FALSE(m[0].read);
    EXPECT_EQ(m[0].len, 1u);
    EXPECT_EQ(m[0].first, ina228::DIAG_ALRT);
    EXPECT_TRUE(m[1].read);
    EXPECT_EQ(m[1].len, 2u);
    if (fresh) {
      ++withResult;
      EXPECT_EQ(m[2].first, ina228::VBUS);
      EXPECT_TRUE(m[3].read);
      EXPECT_EQ(m[3].len, 3u);
      EXPECT_EQ(m[4].first, ina228::CURRENT);
      EXPECT_TRUE(m[5].read);
      EXPECT_EQ(m[5].len, 3u);
    } else {
      ++diagOnly;
    }
  }
  EXPECT_GT(withResult, 0);
  EXPECT_GT(diagOnly, 0);
  EXPECT_NEAR(d.sample().busVolts, 13.2, 0.002);
  EXPECT_NEAR(d.sample().currentA, 50.0, 0.05);
  EXPECT_EQ(chip.protocolErrors(), 0u);
}

TEST_F(Ina228DriverTest, TransactionFailingPartWayUsesNothingOfIt) {
  // A NACK at the VBUS pointer, after DIAG_ALRT was already read: the
  // adapter reports only that the transaction failed, so neither the alert
  // flags nor a result of it are used; the result is read again next tick.
  test::RecordingBus rec(bus);
  Ina228Driver d(rec, kAddr, 0.0005, 200.0);
  ASSERT_EQ(d.setBusOvervoltageLimit(14.8), 0);
  ASSERT_EQ(d.start(t.now), 0);
  d.setFastMode(true);
  for (int i = 0; i < 400; ++i) d.poll(t.now += 2'500'000);
  setPins(14.9, 10.0);  // above BOVL: the chip's DIAG_ALRT now says BUSOL
  rec.failNext(2);
  Ina228Sample before = d.sample();
  Ina228Stats statsBefore = d.stats();
  while (rec.injected() == 0) {
    before = d.sample();
    statsBefore = d.stats();
    d.poll(t.now += 2'500'000);
  }
  const Ina228Sample& s = d.sample();
  EXPECT_FALSE(s.fresh);
  EXPECT_EQ(s.stamp, before.stamp);
  EXPECT_EQ(s.diagStamp, before.diagStamp) << "the DIAG_ALRT read of a failed transaction is not used";
  EXPECT_EQ(s.busOvervoltage, before.busOvervoltage);
  EXPECT_EQ(d.stats().failedReads, statsBefore.failedReads + 1);
  EXPECT_EQ(d.stats().consecutiveFailures, 1u);
  EXPECT_TRUE(d.present());
  // The due result is read at the very next tick.
  const Ina228Sample& next = d.poll(t.now += 2'500'000);
  EXPECT_TRUE(next.fresh);
  EXPECT_EQ(next.diagStamp, t.now);
  EXPECT_EQ(d.stats().consecutiveFailures, 0u);
  for (int i = 0; i < 20; ++i) d.poll(t.now += 2'500'000);
  EXPECT_NEAR(d.sample().busVolts, 14.9, 0.002);
  EXPECT_TRUE(d.sample().busOvervoltage);
  EXPECT_EQ(chip.protocolErrors(), 0u);
}

}  // namespace
}  // namespace xr
