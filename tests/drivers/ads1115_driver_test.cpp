// Ads1115Driver against the simulator's ADS1115 model (drivers/sim): the
// continuous 860 SPS sequence, the MUX rule (a sample is never labelled with
// the wrong channel, whatever the oscillator tolerance), both pacings,
// NACKs and re-detection. Every channel sees a distinct voltage, so a
// mislabelled sample is caught by the value checks.
#include "drivers/ads1115/ads1115_driver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <vector>

#include "drivers/ads1115/ads1115_registers.h"
#include "drivers/frontend/analog_frontend.h"
#include "drivers/sim/ads1115_model.h"
#include "sim_fixture.h"

namespace xr {
namespace {

constexpr std::uint16_t kAddr = 0x48;
constexpr double kBattV = 13.1, kAltA = 42.0, kRpm = 1500.0, kTempF = 150.0;

struct Counts {
  std::array<int, 4> n{};
  std::array<int, 4> wrong{};
  int total() const { return n[0] + n[1] + n[2] + n[3]; }
  int wrongTotal() const { return wrong[0] + wrong[1] + wrong[2] + wrong[3]; }
};

class Ads1115DriverTest : public ::testing::TestWithParam<double> {
 protected:
  explicit Ads1115DriverTest(double clockScale = 1.0) : bus(&t.now), clock(t), chip(clockScale) {
    bus.attach(kAddr, &chip);
    chip.setInputs({frontend::adcFromBatteryVolts(fe, kBattV), frontend::adcFromAltAmps(fe, kAltA),
                    frontend::adcFromRpm(fe, kRpm), frontend::adcFromTempF(fe, kTempF)});
  }
  static bool plausible(int ch, double v) {
    switch (ch) {
      case 0:
        return std::abs(v - kBattV) < 0.01;
      case 1:
        return std::abs(v - kAltA) < 0.02;
      case 2:
        return std::abs(v - kRpm) < 0.5;
      default:
        return std::abs(v - kTempF) < 0.5;
    }
  }
  void tally(const Ads1115Samples& s, Counts& c) {
    for (int ch = 0; ch < 4; ++ch) {
      const auto& x = s.ch[static_cast<std::size_t>(ch)];
      if (!x.fresh) continue;
      ++c.n[static_cast<std::size_t>(ch)];
      if (!plausible(ch, x.value)) ++c.wrong[static_cast<std::size_t>(ch)];
    }
  }
  // Timed pacing: poll every `tick` for `dur`.
  Counts runTimed(Ads1115Driver& d, TimeNs dur, TimeNs tick = 2'500'000) {
    Counts c;
    const TimeNs end = t.now + dur;
    while (t.now < end) {
      t.now += tick;
      tally(d.poll(t.now), c);
    }
    return c;
  }
  // ReadyEdge pacing: find each conversion end in 5 µs steps, hand the edge
  // to the driver `latency` later; `skipEvery` > 0 drops every Nth edge.
  // `beforeEdge(n)` runs before the driver sees edge n (1-based).
  Counts runEdges(Ads1115Driver& d, TimeNs dur, TimeNs latency, int skipEvery = 0,
                  const std::function<void(int)>& beforeEdge = {}) {
    Counts c;
    const TimeNs end = t.now + dur;
    auto seen = chip.conversions();
    int edges = 0;
    while (t.now < end) {
      t.now += 5'000;
      chip.update(t.now);
      if (chip.conversions() == seen) continue;
      seen = chip.conversions();
      ++edges;
      if (skipEvery > 0 && edges % skipEvery == 0) continue;
      const TimeNs edge = t.now;
      t.now += latency;
      if (beforeEdge) beforeEdge(edges);
      d.onReadyEdge(edge);
      seen = chip.conversions();  // the transfers may have advanced the chip
      tally(d.poll(t.now), c);
    }
    return c;
  }
  AnalogFrontEndSettings fe;
  test::VirtualTime t;
  sim::SimI2cBus bus;
  test::VirtualClock clock;
  sim::Ads1115Model chip;
  std::vector<int> seq{1, 0, 1, 2, 1, 3};
};

TEST_F(Ads1115DriverTest, StartsContinuousAt860SpsOnTheFirstChannel) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock);
  ASSERT_EQ(d.start(t.now), 0);
  EXPECT_TRUE(d.present());
  const std::uint16_t cfg = chip.peekConfig();
  EXPECT_EQ(cfg & ads1115::MODE_SINGLE, 0) << "continuous";
  EXPECT_EQ((cfg >> 5) & 7, 7) << "860 SPS";
  EXPECT_EQ(ads1115::muxChannelOf(cfg), 1);
  EXPECT_EQ(cfg & 3, 3) << "comparator off in timed pacing";
}

TEST_F(Ads1115DriverTest, TimedSequenceScalesEveryChannelAndFavoursCh1) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock);
  ASSERT_EQ(d.start(t.now), 0);
  const Counts c = runTimed(d, 1'000'000'000);
  EXPECT_EQ(c.wrongTotal(), 0);
  for (int ch = 0; ch < 4; ++ch) EXPECT_GE(c.n[static_cast<std::size_t>(ch)], 10) << "channel " << ch;
  EXPECT_NEAR(c.n[1], 3 * c.n[0], 3);
  EXPECT_GE(c.total(), 150);
  EXPECT_EQ(chip.protocolErrors(), 0u);
  const auto s = d.poll(t.now);
  EXPECT_NEAR(s.ch[0].value, kBattV, 0.01);
  EXPECT_NEAR(s.ch[1].value, kAltA, 0.02);
  EXPECT_NEAR(s.ch[2].value, kRpm, 0.5);
  EXPECT_NEAR(s.ch[3].value, kTempF, 0.5);
  EXPECT_GT(s.ch[3].stamp, 0);
}

TEST_F(Ads1115DriverTest, FreshFlagsClearAfterPoll) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock);
  ASSERT_EQ(d.start(t.now), 0);
  runTimed(d, 100'000'000);
  const auto s = d.poll(t.now);  // same instant: nothing new
  for (const auto& ch : s.ch) EXPECT_FALSE(ch.fresh);
  EXPECT_GT(s.ch[1].count, 0u);
}

TEST_F(Ads1115DriverTest, InvalidSequenceFallsBackToTheDefault) {
  const std::vector<int> bad{1, 7};
  Ads1115Driver d(bus, kAddr, bad, fe, clock);
  EXPECT_TRUE(d.configError());
  ASSERT_EQ(d.sequence().size(), 6u);
  EXPECT_EQ(d.sequence()[0], 1);
  EXPECT_EQ(d.sequence()[3], 2);
  const std::vector<int> empty;
  Ads1115Driver e(bus, kAddr, empty, fe, clock);
  EXPECT_TRUE(e.configError());
}

TEST_F(Ads1115DriverTest, ConfigurableSequenceWithRepeatsIsHonoured) {
  const std::vector<int> only{1, 1, 1, 0};
  Ads1115Driver d(bus, kAddr, only, fe, clock);
  ASSERT_EQ(d.start(t.now), 0);
  const Counts c = runTimed(d, 1'000'000'000);
  EXPECT_EQ(c.wrongTotal(), 0);
  EXPECT_EQ(c.n[2] + c.n[3], 0);
  EXPECT_GT(c.n[1], 2 * c.n[0]);
}

TEST_F(Ads1115DriverTest, NacksMarkAbsentAndRedetectAfterTheInterval) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock);
  ASSERT_EQ(d.start(t.now), 0);
  runTimed(d, 50'000'000);
  bus.setNack(kAddr, true);
  Counts c = runTimed(d, 100'000'000);
  EXPECT_FALSE(d.present());
  EXPECT_EQ(c.total(), 0);
  EXPECT_GE(d.stats().failedReads, Ads1115Driver::kFailRunForRedetect);
  bus.setNack(kAddr, false);
  runTimed(d, 1'100'000'000);
  EXPECT_TRUE(d.present());
  EXPECT_EQ(d.stats().redetects, 1u);
  c = runTimed(d, 200'000'000);
  EXPECT_GT(c.total(), 0);
  EXPECT_EQ(c.wrongTotal(), 0);
}

TEST_F(Ads1115DriverTest, AbsentAtStartIsAnErrorNotACrash) {
  bus.detach(kAddr);
  Ads1115Driver d(bus, kAddr, seq, fe, clock);
  EXPECT_NE(d.start(t.now), 0);
  EXPECT_FALSE(d.present());
  const auto s = d.poll(t.now + 1000);
  EXPECT_FALSE(s.present);
  EXPECT_TRUE(std::isnan(s.ch[1].value));
}

TEST_F(Ads1115DriverTest, ReadyEdgeUsesEveryConversion) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock, AdsPacing::ReadyEdge);
  ASSERT_EQ(d.start(t.now), 0);
  const std::uint16_t cfg = chip.peekConfig();
  EXPECT_NE(cfg & 3, 3) << "comparator enabled for ALERT/RDY";
  const Counts c = runEdges(d, 1'000'000'000, 150'000);
  EXPECT_EQ(c.wrongTotal(), 0);
  // ~860 conversions/s, two discarded at start: CH1 gets half.
  EXPECT_GE(c.total(), 840);
  EXPECT_GE(c.n[1], 400);
  for (int ch = 0; ch < 4; ++ch) EXPECT_GE(c.n[static_cast<std::size_t>(ch)], 100);
  EXPECT_EQ(chip.protocolErrors(), 0u);
}

TEST_F(Ads1115DriverTest, ReadyEdgeReadsTheResultAndWritesTheNextMuxInOneTransaction) {
  // Pointer to Conversion, the 2-byte result, the Config write for the
  // conversion after next: the same accesses in the same order as two
  // transfers, in one transaction (one I2C_RDWR ioctl on the board).
  test::RecordingBus rec(bus);
  Ads1115Driver d(rec, kAddr, seq, fe, clock, AdsPacing::ReadyEdge);
  ASSERT_EQ(d.start(t.now), 0);
  int checked = 0;
  runEdges(d, 100'000'000, 150'000, 0, [&](int n) {
    if (n > 1) {
      ASSERT_EQ(rec.sizes().size(), 1u) << "one transaction per edge";
      const auto& m = rec.log();
      ASSERT_EQ(m.size(), 3u);
      EXPECT_FALSE(m[0].read);
      EXPECT_EQ(m[0].len, 1u);
      EXPECT_EQ(m[0].first, ads1115::CONVERSION);
      EXPECT_TRUE(m[1].read);
      EXPECT_EQ(m[1].len, 2u);
      EXPECT_FALSE(m[2].read);
      EXPECT_EQ(m[2].len, 3u);
      EXPECT_EQ(m[2].first, ads1115::CONFIG);
      ++checked;
    }
    rec.clear();
  });
  EXPECT_GT(checked, 50);
  EXPECT_EQ(chip.protocolErrors(), 0u);
}

TEST_F(Ads1115DriverTest, ReadyEdgeTransactionFailingPartWayFlushesAndNeverMislabels) {
  // A NACK at the Config write (the result was already read) or at the
  // result read: which part failed is unknown, so the result is dropped and
  // the pipeline flushed (the chip may hold either MUX); labels stay right.
  for (int failAt : {1, 2}) {
    test::RecordingBus rec(bus);
    Ads1115Driver d(rec, kAddr, seq, fe, clock, AdsPacing::ReadyEdge);
    ASSERT_EQ(d.start(t.now), 0);
    const Counts c = runEdges(d, 1'000'000'000, 150'000, 0, [&](int n) {
      // Every 11th edge: 11 is prime to the 6-entry sequence, so the
      // failures hit every channel's turn (not one phase over and over).
      if (n % 11 == 0) rec.failNext(failAt);
    });
    EXPECT_EQ(c.wrongTotal(), 0) << "fail at message " << failAt;
    EXPECT_GT(rec.injected(), 50);
    EXPECT_GE(d.stats().failedReads, static_cast<unsigned long>(rec.injected()));
    EXPECT_GE(d.stats().pipelineFlushes, static_cast<unsigned long>(rec.injected()));
    EXPECT_TRUE(d.present()) << "isolated failures are tolerated";
    EXPECT_GT(c.total(), 300);
    for (int ch = 0; ch < 4; ++ch) EXPECT_GT(c.n[static_cast<std::size_t>(ch)], 20) << "channel " << ch;
    EXPECT_EQ(chip.protocolErrors(), 0u);
  }
}

TEST_F(Ads1115DriverTest, ReadyEdgeValuesEqualTheFrontEndConversions) {
  // accept() inlines/caches the front-end conversions (CH1 scale, CH3 log
  // for a repeated code): every value must equal frontend::*FromAdc of its
  // ADC volts, bit for bit, whether the code repeats or changes.
  Ads1115Driver d(bus, kAddr, seq, fe, clock, AdsPacing::ReadyEdge);
  ASSERT_EQ(d.start(t.now), 0);
  int checked = 0;
  auto check = [&](const Ads1115Samples& s) {
    for (int ch = 0; ch < 4; ++ch) {
      const auto& x = s.ch[static_cast<std::size_t>(ch)];
      if (!x.fresh) continue;
      const double want = ch == 0   ? frontend::batteryVoltsFromAdc(fe, x.adcVolts)
                          : ch == 1 ? frontend::altAmpsFromAdc(fe, x.adcVolts)
                          : ch == 2 ? frontend::rpmFromAdc(fe, x.adcVolts)
                                    : frontend::tempFFromAdc(fe, x.adcVolts);
      EXPECT_EQ(x.value, want) << "channel " << ch;
      ++checked;
    }
  };
  double tempF = 120.0;
  for (int step = 0; step < 40; ++step) {
    // Change every input now and then; in between the codes repeat.
    if (step % 4 == 0) {
      tempF += 3.7;
      chip.setInputs({frontend::adcFromBatteryVolts(fe, 12.0 + step * 0.05),
                      frontend::adcFromAltAmps(fe, -20.0 + step * 2.1),
                      frontend::adcFromRpm(fe, 900.0 + step * 40), frontend::adcFromTempF(fe, tempF)});
    }
    const TimeNs end = t.now + 10'000'000;
    auto seen = chip.conversions();
    while (t.now < end) {
      t.now += 5'000;
      chip.update(t.now);
      if (chip.conversions() == seen) continue;
      const TimeNs edge = t.now;
      t.now += 100'000;
      d.onReadyEdge(edge);
      seen = chip.conversions();
      check(d.poll(t.now));
    }
  }
  EXPECT_GT(checked, 300);
}

TEST_F(Ads1115DriverTest, ReadyEdgeLateServiceFlushesInsteadOfMislabelling) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock, AdsPacing::ReadyEdge);
  ASSERT_EQ(d.start(t.now), 0);
  // Handled after more than one data period: attribution is ambiguous.
  const Counts c = runEdges(d, 200'000'000, 1'300'000);
  EXPECT_EQ(c.wrongTotal(), 0);
  EXPECT_GT(d.stats().pipelineFlushes, 0u);
}

TEST_F(Ads1115DriverTest, ReadyEdgeMissedEdgesFlushInsteadOfMislabelling) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock, AdsPacing::ReadyEdge);
  ASSERT_EQ(d.start(t.now), 0);
  const Counts c = runEdges(d, 1'000'000'000, 100'000, /*skipEvery=*/7);
  EXPECT_EQ(c.wrongTotal(), 0);
  EXPECT_GT(d.stats().pipelineFlushes, 50u);
  EXPECT_GT(c.total(), 300);
}

// The oscillator may run 10 % slow or fast: no sample is ever mislabelled.
class Ads1115OscillatorTest : public Ads1115DriverTest {
 protected:
  Ads1115OscillatorTest() : Ads1115DriverTest(GetParam()) {}
};

TEST_P(Ads1115OscillatorTest, TimedNeverMislabels) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock);
  ASSERT_EQ(d.start(t.now), 0);
  const Counts c = runTimed(d, 1'000'000'000, 2'500'000);
  EXPECT_EQ(c.wrongTotal(), 0);
  EXPECT_GT(c.total(), 150);
  // A control loop at another rate.
  const Counts c2 = runTimed(d, 1'000'000'000, 1'000'000);
  EXPECT_EQ(c2.wrongTotal(), 0);
  EXPECT_GT(c2.total(), 300);
}

TEST_P(Ads1115OscillatorTest, ReadyEdgeNeverMislabels) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock, AdsPacing::ReadyEdge);
  ASSERT_EQ(d.start(t.now), 0);
  const Counts c = runEdges(d, 500'000'000, 200'000);
  EXPECT_EQ(c.wrongTotal(), 0);
  EXPECT_GT(c.total(), 350);
}

INSTANTIATE_TEST_SUITE_P(ClockTolerance, Ads1115OscillatorTest, ::testing::Values(0.9, 1.0, 1.1));

}  // namespace
}  // namespace xr

#include "drivers/ads1115/ads1115_inputs.h"

namespace xr {
namespace {

TEST_F(Ads1115DriverTest, FillsTheCoreInputs) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock);
  ASSERT_EQ(d.start(t.now), 0);
  Inputs in;
  int ch1Fresh = 0;
  for (int i = 0; i < 400; ++i) {
    t.now += 2'500'000;
    fillAdsInputs(d.poll(t.now), in);
    ch1Fresh += in.altCurrentRaw.fresh ? 1 : 0;
  }
  EXPECT_GT(ch1Fresh, 50);
  EXPECT_NEAR(in.BatteryV.value, kBattV, 0.01);
  EXPECT_NEAR(in.altCurrentRaw.value, kAltA, 0.02);
  EXPECT_NEAR(in.rpm.value, kRpm, 0.5);
  EXPECT_NEAR(in.thermistorF.value, kTempF, 0.5);
}

}  // namespace
}  // namespace xr

namespace xr {
namespace {

TEST_F(Ads1115DriverTest, TimedChipResetBehindOurBackIsNeverReadAsASample) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock);
  ASSERT_EQ(d.start(t.now), 0);
  Counts c = runTimed(d, 100'000'000);
  EXPECT_EQ(c.wrongTotal(), 0);
  // Power glitch: a chip with reset registers (single-shot, result 0) answers.
  sim::Ads1115Model fresh;
  fresh.setInputs({frontend::adcFromBatteryVolts(fe, kBattV), frontend::adcFromAltAmps(fe, kAltA),
                   frontend::adcFromRpm(fe, kRpm), frontend::adcFromTempF(fe, kTempF)});
  bus.attach(kAddr, &fresh);
  c = runTimed(d, 500'000'000);
  EXPECT_EQ(c.wrongTotal(), 0) << "the zero result of a reset chip must not become a sample";
  EXPECT_GE(d.stats().reconfigures, 1u);
  EXPECT_GT(c.total(), 50);
  EXPECT_EQ(fresh.protocolErrors(), 0u);
}

TEST_F(Ads1115DriverTest, ReadyEdgeChipResetIsRepairedByThePeriodicCheck) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock, AdsPacing::ReadyEdge);
  ASSERT_EQ(d.start(t.now), 0);
  runEdges(d, 100'000'000, 100'000);
  sim::Ads1115Model fresh;
  fresh.setInputs({frontend::adcFromBatteryVolts(fe, kBattV), frontend::adcFromAltAmps(fe, kAltA),
                   frontend::adcFromRpm(fe, kRpm), frontend::adcFromTempF(fe, kTempF)});
  bus.attach(kAddr, &fresh);
  // No edges from a powered-down chip: the runtime keeps polling on timeouts.
  for (int i = 0; i < 500; ++i) d.poll(t.now += 2'500'000);
  EXPECT_GE(d.stats().reconfigures, 1u);
  EXPECT_EQ(fresh.peekConfig() & ads1115::MODE_SINGLE, 0) << "continuous again";
}

}  // namespace
}  // namespace xr

namespace xr {
namespace {

TEST_F(Ads1115DriverTest, SingleShotGivesOneLabelledSamplePerTick) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock, AdsPacing::SingleShot);
  ASSERT_EQ(d.start(t.now), 0);
  EXPECT_NE(chip.peekConfig() & ads1115::MODE_SINGLE, 0);
  const Counts c = runTimed(d, 1'000'000'000);
  EXPECT_EQ(c.wrongTotal(), 0);
  EXPECT_GE(c.total(), 395) << "a sample every 2.5 ms tick";
  EXPECT_GE(c.n[1], 195);
  EXPECT_EQ(chip.protocolErrors(), 0u);
}

TEST_F(Ads1115DriverTest, SingleShotChipResetIsNeverReadAsASample) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock, AdsPacing::SingleShot);
  ASSERT_EQ(d.start(t.now), 0);
  runTimed(d, 100'000'000);
  sim::Ads1115Model fresh;
  fresh.setInputs({frontend::adcFromBatteryVolts(fe, kBattV), frontend::adcFromAltAmps(fe, kAltA),
                   frontend::adcFromRpm(fe, kRpm), frontend::adcFromTempF(fe, kTempF)});
  bus.attach(kAddr, &fresh);
  const Counts c = runTimed(d, 500'000'000);
  EXPECT_EQ(c.wrongTotal(), 0);
  EXPECT_GE(d.stats().reconfigures, 1u);
  EXPECT_GT(c.total(), 150);
}

TEST_F(Ads1115DriverTest, SingleShotNacksThenRecovers) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock, AdsPacing::SingleShot);
  ASSERT_EQ(d.start(t.now), 0);
  runTimed(d, 50'000'000);
  bus.setNack(kAddr, true);
  runTimed(d, 100'000'000);
  EXPECT_FALSE(d.present());
  bus.setNack(kAddr, false);
  runTimed(d, 1'100'000'000);
  EXPECT_TRUE(d.present());
  const Counts c = runTimed(d, 200'000'000);
  EXPECT_GT(c.total(), 50);
  EXPECT_EQ(c.wrongTotal(), 0);
}

TEST_P(Ads1115OscillatorTest, SingleShotNeverMislabels) {
  Ads1115Driver d(bus, kAddr, seq, fe, clock, AdsPacing::SingleShot);
  ASSERT_EQ(d.start(t.now), 0);
  const Counts c = runTimed(d, 1'000'000'000, 2'500'000);
  EXPECT_EQ(c.wrongTotal(), 0);
  EXPECT_GT(c.total(), 390);
  const Counts c2 = runTimed(d, 1'000'000'000, 1'000'000);
  EXPECT_EQ(c2.wrongTotal(), 0);
  EXPECT_GT(c2.total(), 450);
}

// The driver scales each conversion by one factor per channel: that must be
// codeToVolts bit for bit, for every code at every PGA (a factor rounded
// differently, e.g. fullScale * (1 / 32768.0) computed another way or a
// division kept on one side only, would show up here).
// codeToVolts is code x (FSR / 2^15): bit for bit the datasheet's code x FSR / 2^15.
TEST(Ads1115Registers, CodeToVoltsIsTheDatasheetFormulaBitForBit) {
  for (unsigned pga = 0; pga < 8; ++pga) {
    for (std::uint32_t raw = 0; raw <= 0xFFFF; ++raw) {
      const auto code = static_cast<std::uint16_t>(raw);
      const double a = static_cast<std::int16_t>(code) * ads1115::fullScaleVolts(pga) / 32768.0;
      const double b = ads1115::codeToVolts(code, pga);
      std::uint64_t ba = 0, bb = 0;
      std::memcpy(&ba, &a, sizeof a);
      std::memcpy(&bb, &b, sizeof b);
      ASSERT_EQ(ba, bb) << "pga " << pga << " code " << raw;
    }
  }
}

}  // namespace
}  // namespace xr
