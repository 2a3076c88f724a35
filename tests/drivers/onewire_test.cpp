// DS18B20 over w1 sysfs: the w1_slave parser (docs/sources.md, datasheet facts §3) and the
// reader on a fake /sys/bus/w1/devices tree.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

#include "drivers/onewire/ds18b20_reader.h"
#include "drivers/onewire/w1_therm.h"
#include "runtime/ds18b20_handoff.h"
#include "temp_dir.h"

namespace xr {
namespace {

constexpr const char* kGood = "2c 01 ff ff 7f ff ff ff 61 : crc=61 YES\n2c 01 ff ff 7f ff ff ff 61 t=18750\n";

TEST(W1Slave, ParsesTheDocumentedExample) {
  const auto r = w1::parseW1Slave(kGood);
  EXPECT_EQ(r.error, w1::ParseError::None);
  EXPECT_EQ(r.milliC, 18750);
}

TEST(W1Slave, NegativeTemperature) {
  const auto r =
      w1::parseW1Slave("5e ff 4b 46 7f ff 02 10 41 : crc=41 YES\n5e ff 4b 46 7f ff 02 10 41 t=-10125\n");
  EXPECT_EQ(r.error, w1::ParseError::None);
  EXPECT_EQ(r.milliC, -10125);
}

TEST(W1Slave, CrcNoIsRejectedEvenWithATemperature) {
  const auto r =
      w1::parseW1Slave("2c 01 ff ff 7f ff ff ff 62 : crc=61 NO\n2c 01 ff ff 7f ff ff ff 61 t=18750\n");
  EXPECT_EQ(r.error, w1::ParseError::CrcNo);
}

TEST(W1Slave, PowerOnValueIsRejected) {
  const auto r =
      w1::parseW1Slave("50 05 4b 46 7f ff 0c 10 1c : crc=1c YES\n50 05 4b 46 7f ff 0c 10 1c t=85000\n");
  EXPECT_EQ(r.error, w1::ParseError::PowerOnValue);
}

TEST(W1Slave, EmptyAndGarbage) {
  EXPECT_EQ(w1::parseW1Slave("").error, w1::ParseError::Empty);
  EXPECT_EQ(w1::parseW1Slave("garbage").error, w1::ParseError::Malformed);
  EXPECT_EQ(w1::parseW1Slave("aa : crc=61 YES\nno temperature\n").error, w1::ParseError::Malformed);
  EXPECT_EQ(w1::parseW1Slave("aa : crc=61 YES\naa t=12x\n").error, w1::ParseError::Malformed);
  EXPECT_EQ(w1::parseW1Slave("aa : crc=61 YES\naa t=300000\n").error, w1::ParseError::Malformed);
}

TEST(W1Slave, ListsOnlyFamily28Sorted) {
  test::TempDir d;
  test::writeFile(d / "28-0000000002/w1_slave", kGood);
  test::writeFile(d / "28-0000000001/w1_slave", kGood);
  test::writeFile(d / "10-000000000a/w1_slave", kGood);
  test::writeFile(d / "w1_bus_master1/x", "");
  const auto l = w1::listDs18b20(d.path());
  ASSERT_EQ(l.size(), 2u);
  EXPECT_EQ(l[0], "28-0000000001");
  EXPECT_EQ(l[1], "28-0000000002");
  EXPECT_TRUE(w1::listDs18b20(d / "missing").empty());
}

class Ds18b20ReaderTest : public ::testing::Test {
 protected:
  TimeNs fakeNow = 5'000'000'000;
  Ds18b20Reader::NowFn now() {
    return [this] { return fakeNow; };
  }
  test::TempDir d;
};

TEST_F(Ds18b20ReaderTest, PublishesFahrenheitStampAndHeartbeat) {
  test::writeFile(d / "28-00000abc/w1_slave", kGood);
  Ds18b20Reader r(d.path(), "", 1'000'000'000, now());
  r.readOnce();
  const auto s = r.latest();
  EXPECT_TRUE(s.sensorFound);
  EXPECT_NEAR(s.tempF, 18.75 * 9 / 5 + 32, 1e-9);
  EXPECT_EQ(s.stamp, fakeNow);
  EXPECT_EQ(s.heartbeat, fakeNow);
  EXPECT_EQ(s.good, 1u);
}

// The board's hand-off: each cycle's sample reaches the sink once, on the
// reader's thread, equal to what latest() then returns (good or bad).
TEST_F(Ds18b20ReaderTest, EachCycleHandsItsSampleToTheSinkOnce) {
  test::writeFile(d / "28-00000abc/w1_slave", kGood);
  Ds18b20Reader r(d.path(), "28-00000abc", 1'000'000'000, now());
  std::vector<Ds18b20Sample> seen;
  r.onSample([&seen](const Ds18b20Sample& s) { seen.push_back(s); });
  r.readOnce();
  fakeNow += 1'000'000'000;
  test::writeFile(d / "28-00000abc/w1_slave", "garbage\n");
  r.readOnce();
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].stamp, 5'000'000'000);
  EXPECT_EQ(seen[1].heartbeat, fakeNow) << "a bad read still beats the heart";
  EXPECT_EQ(seen[1].stamp, 5'000'000'000) << "and keeps the last good stamp";
  EXPECT_EQ(seen[1].bad, r.latest().bad);
  EXPECT_EQ(seen[1].heartbeat, r.latest().heartbeat);
}

TEST_F(Ds18b20ReaderTest, BadReadKeepsTheOldStampButBeatsTheHeart) {
  test::writeFile(d / "28-00000abc/w1_slave", kGood);
  Ds18b20Reader r(d.path(), "28-00000abc", 1'000'000'000, now());
  r.readOnce();
  const TimeNs firstStamp = fakeNow;
  fakeNow += 1'000'000'000;
  test::writeFile(d / "28-00000abc/w1_slave",
                  "2c 01 ff ff 7f ff ff ff 62 : crc=61 NO\n2c 01 ff ff 7f ff ff ff 61 t=99000\n");
  r.readOnce();
  const auto s = r.latest();
  EXPECT_EQ(s.stamp, firstStamp) << "T5 sees the sample age grow";
  EXPECT_EQ(s.heartbeat, fakeNow) << "T4 sees the task alive";
  EXPECT_NEAR(s.tempF, 18.75 * 9 / 5 + 32, 1e-9);
  EXPECT_EQ(s.lastError, w1::ParseError::CrcNo);
  EXPECT_EQ(s.bad, 1u);
}

TEST_F(Ds18b20ReaderTest, MissingSensorIsReportedAndPickedUpLater) {
  Ds18b20Reader r(d.path(), "", 1'000'000'000, now());
  r.readOnce();
  EXPECT_FALSE(r.latest().sensorFound);
  EXPECT_EQ(r.latest().stamp, 0);
  test::writeFile(d / "28-00000def/w1_slave", kGood);
  r.readOnce();
  EXPECT_TRUE(r.latest().sensorFound);
  EXPECT_GT(r.latest().stamp, 0);
}

TEST_F(Ds18b20ReaderTest, ThreadPublishesAndStops) {
  test::writeFile(d / "28-00000abc/w1_slave", kGood);
  Ds18b20Reader r(d.path(), "", 1'000'000);  // real monotonic clock, 1 ms period
  r.start();
  // Wait (bounded) for a publication; no timing is asserted.
  for (int i = 0; i < 2000 && r.latest().good < 2; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  r.stop();
  EXPECT_GE(r.latest().good, 2u);
  EXPECT_GT(r.latest().heartbeat, 0);
}

// a second DS18B20 (the battery's) on the same bus.
TEST_F(Ds18b20ReaderTest, FirstFoundSkipsTheBatterySensor) {
  test::writeFile(d / "28-000000000001/w1_slave", kGood);  // the battery's, sorts first
  test::writeFile(d / "28-00000abc/w1_slave",
                  "5e ff 4b 46 7f ff 02 10 41 : crc=41 YES\n5e ff 4b 46 7f ff 02 10 41 t=-10125\n");
  Ds18b20Reader alt(d.path(), "", 1'000'000'000, now());
  alt.excludeId("28-000000000001");
  alt.readOnce();
  EXPECT_EQ(alt.sensorPath(), d.path() + "/28-00000abc/w1_slave");
  EXPECT_NEAR(alt.latest().tempF, -10.125 * 9 / 5 + 32, 1e-9);
  // Without the exclusion the first found would have been the battery's.
  Ds18b20Reader plain(d.path(), "", 1'000'000'000, now());
  plain.readOnce();
  EXPECT_EQ(plain.sensorPath(), d.path() + "/28-000000000001/w1_slave");
}

TEST_F(Ds18b20ReaderTest, BatterySampleBecomesAHandoffInCelsiusNamingItsSource) {
  test::writeFile(d / "28-000000000001/w1_slave", kGood);
  Ds18b20Reader bat(d.path(), "28-000000000001", 1'000'000'000, now());
  rt::BatteryTempHandoff before = batteryTempHandoff(bat.latest());
  EXPECT_EQ(before.source, BatteryTempSource::ds18b20);  // a sensor is expected before its first reading
  EXPECT_EQ(before.stamp, 0);
  EXPECT_TRUE(std::isnan(before.tempC));
  bat.readOnce();
  const rt::BatteryTempHandoff h = batteryTempHandoff(bat.latest());
  EXPECT_NEAR(h.tempC, 18.75, 1e-9);
  EXPECT_EQ(h.stamp, fakeNow);
}

}  // namespace
}  // namespace xr
