// The simulated bus hands each run of messages to one address to the chip in
// one transact(): the outcome must stay the one of dispatching the messages
// singly (refusals, NACKs, missing buffers; what ran before a failure).
#include "drivers/sim/sim_i2c_bus.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <cstdint>

#include "drivers/sim/ads1115_model.h"
#include "drivers/sim/ina228_model.h"

namespace xr::sim {
namespace {
using namespace ina228;

struct Board {
  TimeNs now = 0;
  SimI2cBus bus{&now};
  Ina228Model ina;
  Ads1115Model ads;
  Board() {
    bus.attach(0x40, &ina);
    bus.attach(0x48, &ads);
  }
};

TEST(SimI2cBus, BadPointerInACombinedTransactionNacksAfterTheMessagesBeforeIt) {
  Board b;
  // SHUNT_CAL write, then a pointer to a reserved INA228 address, then a read.
  std::uint8_t cal[3] = {SHUNT_CAL, 0x0F, 0xA0};
  std::uint8_t bad = 0x20, rx[2] = {0xEE, 0xEE};
  I2cMsg m[3] = {{0x40, false, cal, 3}, {0x40, false, &bad, 1}, {0x40, true, rx, 2}};
  EXPECT_EQ(b.bus.transfer(m), EREMOTEIO);
  EXPECT_EQ(b.ina.protocolErrors(), 1u);
  EXPECT_EQ(b.ina.peek(SHUNT_CAL), 0x0FA0u) << "the write before the refused pointer took effect";
  EXPECT_EQ(rx[0], 0xEE) << "the read after it never ran";
  EXPECT_EQ(b.bus.failedTransfers(), 1u);
  // ADS1115: pointer bits 7:2 set, after a valid Lo_thresh write.
  std::uint8_t lo[3] = {2, 0x12, 0x34};
  std::uint8_t badAds = 0x04;
  I2cMsg a[3] = {{0x48, false, lo, 3}, {0x48, false, &badAds, 1}, {0x48, true, rx, 2}};
  EXPECT_EQ(b.bus.transfer(a), EREMOTEIO);
  EXPECT_EQ(b.ads.protocolErrors(), 1u);
  std::uint8_t p = 2;
  I2cMsg rd[2] = {{0x48, false, &p, 1}, {0x48, true, rx, 2}};
  ASSERT_EQ(b.bus.transfer(rd), 0);
  EXPECT_EQ(rx[0], 0x12);
  EXPECT_EQ(rx[1], 0x34);
  // A write to the read-only Conversion register and a 3-byte read are refused too.
  std::uint8_t conv[3] = {0, 0, 0}, rx3[3] = {};
  I2cMsg c[1] = {{0x48, false, conv, 3}};
  EXPECT_EQ(b.bus.transfer(c), EREMOTEIO);
  I2cMsg r3[2] = {{0x48, false, &p, 1}, {0x48, true, rx3, 3}};
  EXPECT_EQ(b.bus.transfer(r3), EREMOTEIO);
  EXPECT_EQ(b.ads.protocolErrors(), 3u);
}

TEST(SimI2cBus, MissingBufferFailsWithEfaultBeforeReachingTheChip) {
  Board b;
  std::uint8_t cal[3] = {SHUNT_CAL, 0x12, 0x34};
  std::uint8_t rx[2] = {};
  I2cMsg m[3] = {{0x40, false, cal, 3}, {0x40, true, nullptr, 2}, {0x40, true, rx, 2}};
  EXPECT_EQ(b.bus.transfer(m), EFAULT);
  EXPECT_EQ(b.ina.protocolErrors(), 0u) << "the chip never saw the bufferless message";
  EXPECT_EQ(b.ina.peek(SHUNT_CAL), 0x1234u);
  // First message without a buffer: nothing runs.
  I2cMsg first[2] = {{0x40, false, nullptr, 3}, {0x40, false, cal, 3}};
  cal[1] = 0x00;
  EXPECT_EQ(b.bus.transfer(first), EFAULT);
  EXPECT_EQ(b.ina.peek(SHUNT_CAL), 0x1234u);
  EXPECT_EQ(b.bus.failedTransfers(), 2u);
  EXPECT_EQ(b.bus.transfers(), 2u);
  // Empty transfer.
  EXPECT_EQ(b.bus.transfer({}), EINVAL);
}

TEST(SimI2cBus, TransactionAcrossTwoChipsStopsAtTheNackingOne) {
  Board b;
  std::uint8_t cal[3] = {SHUNT_CAL, 0x0F, 0xA0};
  std::uint8_t lo[3] = {2, 0x00, 0x10};
  I2cMsg m[2] = {{0x40, false, cal, 3}, {0x48, false, lo, 3}};
  b.bus.setNack(0x48, true);
  EXPECT_EQ(b.bus.transfer(m), EREMOTEIO);
  EXPECT_EQ(b.ina.peek(SHUNT_CAL), 0x0FA0u);
  EXPECT_EQ(b.ads.protocolErrors(), 0u);
  b.bus.setNack(0x48, false);
  cal[1] = 0x0E;
  ASSERT_EQ(b.bus.transfer(m), 0);
  EXPECT_EQ(b.ina.peek(SHUNT_CAL), 0x0EA0u);
  std::uint8_t p = 2, rx[2] = {};
  I2cMsg rd[2] = {{0x48, false, &p, 1}, {0x48, true, rx, 2}};
  ASSERT_EQ(b.bus.transfer(rd), 0);
  EXPECT_EQ(rx[1], 0x10);
  // Detached: absent.
  b.bus.detach(0x40);
  EXPECT_EQ(b.bus.transfer(m), EREMOTEIO);
  // Each transaction counts once, whichever path (one chip or several) ran
  // it: two-chip m three times, one-chip rd once; two of them failed.
  EXPECT_EQ(b.bus.transfers(), 4u);
  EXPECT_EQ(b.bus.failedTransfers(), 2u);
}

TEST(SimI2cBus, NullClockReadsAsTimeZero) {
  SimI2cBus bus{nullptr};
  Ads1115Model ads;
  bus.attach(0x48, &ads);
  std::uint8_t p = 2, rx[2] = {};
  I2cMsg rd[2] = {{0x48, false, &p, 1}, {0x48, true, rx, 2}};
  ASSERT_EQ(bus.transfer(rd), 0);
  EXPECT_EQ(bus.transfers(), 1u);
  EXPECT_EQ(bus.failedTransfers(), 0u);
}

TEST(SimI2cBus, TransactBringsTheChipToTheBusTime) {
  Board b;
  // ADS1115 single-shot AIN0-GND, ±4.096 V, 860 SPS: the result is there once
  // the bus time passes the data period, without an explicit update().
  b.ads.setInputs({1.0, 0, 0, 0});
  std::uint8_t cfg[3] = {1, std::uint8_t(0x80 | (4 << 4) | (1 << 1) | 1), std::uint8_t((7 << 5) | 3)};
  I2cMsg w[1] = {{0x48, false, cfg, 3}};
  ASSERT_EQ(b.bus.transfer(w), 0);
  b.now = fromMs(2);
  std::uint8_t p = 0, rx[2] = {};
  I2cMsg rd[2] = {{0x48, false, &p, 1}, {0x48, true, rx, 2}};
  ASSERT_EQ(b.bus.transfer(rd), 0);
  EXPECT_EQ((rx[0] << 8) | rx[1], 8000);  // 1 V / 125 uV
}

}  // namespace
}  // namespace xr::sim
