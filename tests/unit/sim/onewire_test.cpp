// Simulated w1 sysfs tree in the kernel's w1_slave format.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "drivers/onewire/ds18b20_reader.h"
#include "drivers/sim/sim_onewire.h"

namespace xr::sim {
namespace {
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

struct TempDir {
  fs::path p;
  TempDir() {
    p = fs::temp_directory_path() / ("xr-w1-test-" + std::to_string(::getpid()) + "-" +
                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(p);
  }
  ~TempDir() { fs::remove_all(p); }
};

TEST(SimOneWire, Crc8MatchesAKnownScratchpad) {
  // A real DS18B20 line from the kernel: "72 01 4b 46 7f ff 0e 10 57 : crc=57 YES".
  const std::uint8_t sp[8] = {0x72, 0x01, 0x4b, 0x46, 0x7f, 0xff, 0x0e, 0x10};
  EXPECT_EQ(SimOneWire::crc8(sp, 8), 0x57);
}

TEST(SimOneWire, FormatIsTwoLinesWithCrcAndMillidegrees) {
  const std::string s = SimOneWire::formatW1Slave(0x0191, false);  // 25.0625 C
  std::istringstream in(s);
  std::string l1, l2;
  std::getline(in, l1);
  std::getline(in, l2);
  EXPECT_EQ(l1.substr(0, 24), "91 01 4b 46 7f ff 0c 10 ");
  EXPECT_NE(l1.find(": crc="), std::string::npos);
  EXPECT_EQ(l1.substr(l1.size() - 3), "YES");
  EXPECT_EQ(l2.substr(l2.size() - 7), "t=25062");
  const std::string bad = SimOneWire::formatW1Slave(0x0191, true);
  EXPECT_NE(bad.find(" NO\n"), std::string::npos);
  EXPECT_NE(SimOneWire::formatW1Slave(std::int16_t(-160), false).find("t=-10000"), std::string::npos);
}

TEST(SimOneWire, WritesOncePerConversionAndOnlyOnChange) {
  TempDir d;
  SimOneWire w(d.p);
  w.update(0, 30.0);
  ASSERT_TRUE(fs::exists(w.slavePath()));
  EXPECT_NE(slurp(w.slavePath()).find("t=30000"), std::string::npos);
  w.update(fromMs(100), 40.0);  // still converting
  EXPECT_NE(slurp(w.slavePath()).find("t=30000"), std::string::npos);
  w.update(fromMs(800), 30.0);  // same value: no rewrite
  EXPECT_EQ(w.writes(), 1u);
  w.update(fromMs(1600), 40.0);
  EXPECT_NE(slurp(w.slavePath()).find("t=40000"), std::string::npos);
  EXPECT_EQ(w.writes(), 2u);
}

TEST(SimOneWire, ConvertNowRewritesAtTheNextUpdate) {
  TempDir d;
  SimOneWire w(d.p);
  w.update(0, 30.0);
  EXPECT_EQ(w.nextConversion(), fromMs(750));
  w.update(fromMs(100), 50.0);  // still converting: no new value
  EXPECT_NE(slurp(w.slavePath()).find("t=30000"), std::string::npos);
  w.convertNow();  // a fault changed what the sensor sees
  EXPECT_EQ(w.nextConversion(), 0);
  w.update(fromMs(200), 50.0);
  EXPECT_NE(slurp(w.slavePath()).find("t=50000"), std::string::npos);
  EXPECT_EQ(w.writes(), 2u);
  EXPECT_EQ(w.nextConversion(), fromMs(950));
  w.setPresent(false);
  EXPECT_GT(w.nextConversion(), fromSec(1e6)) << "absent: never due";
}

TEST(SimOneWire, DisconnectRemovesTheDevice) {
  TempDir d;
  SimOneWire w(d.p);
  w.update(0, 30.0);
  w.setPresent(false);
  EXPECT_FALSE(fs::exists(w.slavePath()));
  w.update(fromSec(5), 30.0);
  EXPECT_FALSE(fs::exists(w.slavePath()));
  w.setPresent(true);
  w.update(fromSec(6), 31.0);
  EXPECT_TRUE(fs::exists(w.slavePath()));
}

TEST(SimOneWire, AShorterReadingLeavesNoOldTail) {
  TempDir d;
  SimOneWire w(d.p);
  w.update(0, 100.0);          // t=100000
  w.update(fromMs(800), 5.0);  // t=5000, rewritten in place
  EXPECT_EQ(slurp(w.slavePath()), SimOneWire::formatW1Slave(5 * 16, false));
  w.update(fromMs(1600), -10.0);
  EXPECT_EQ(slurp(w.slavePath()), SimOneWire::formatW1Slave(-10 * 16, false));
}

// The real reader keeps w1_slave open between readings; the simulated tree
// must still show it every new reading, a disconnect and a reconnect.
TEST(SimOneWire, HeldOpenReaderSeesRewritesDisconnectAndReconnect) {
  TempDir d;
  SimOneWire w(d.p);
  TimeNs now = 0;
  Ds18b20Reader r(d.p.string(), w.deviceId(), fromSec(1), [&] { return now; });
  // The sensor converts tempC at second s and the reader reads right after.
  auto convertAndRead = [&](int s, double tempC) {
    now = fromSec(s);
    w.update(now, tempC);
    r.readOnce();
  };
  convertAndRead(1, 100.0);
  EXPECT_TRUE(r.latest().sensorFound);
  EXPECT_DOUBLE_EQ(r.latest().tempF, 212.0);

  convertAndRead(2, 5.0);  // a shorter file, rewritten under the open reader
  EXPECT_DOUBLE_EQ(r.latest().tempF, 41.0);
  EXPECT_EQ(r.latest().good, 2u);

  w.setPresent(false);
  convertAndRead(3, 50.0);  // absent: nothing converts
  EXPECT_FALSE(r.latest().sensorFound);
  EXPECT_EQ(r.latest().bad, 1u);
  EXPECT_EQ(r.latest().stamp, fromSec(2)) << "no reading while the sensor is gone";

  w.setPresent(true);
  convertAndRead(4, 20.0);
  EXPECT_TRUE(r.latest().sensorFound);
  EXPECT_DOUBLE_EQ(r.latest().tempF, 68.0);
  EXPECT_EQ(r.latest().stamp, fromSec(4));

  // Gone and back between two readings: the held file is the old, emptied
  // one; the reader must find the new file, not report the sensor missing.
  w.setPresent(false);
  w.setPresent(true);
  convertAndRead(5, 30.0);
  EXPECT_TRUE(r.latest().sensorFound);
  EXPECT_DOUBLE_EQ(r.latest().tempF, 86.0);
  EXPECT_EQ(r.latest().good, 4u);
}

// The kernel's format through printf, as the simulator wrote it before it
// formatted by hand: every reading the DS18B20 can give, both CRC states.
std::string printfW1Slave(std::int16_t raw, bool corrupt) {
  std::uint8_t sp[9] = {
      std::uint8_t(raw & 0xFF), std::uint8_t((raw >> 8) & 0xFF), 0x4B, 0x46, 0x7F, 0xFF, 0x0C, 0x10, 0};
  const std::uint8_t crc = SimOneWire::crc8(sp, 8);
  sp[8] = corrupt ? std::uint8_t(crc ^ 0x5A) : crc;
  std::string bytes;
  char b[4];
  for (auto x : sp) {
    std::snprintf(b, sizeof b, "%02x ", x);
    bytes += b;
  }
  char tail[48];
  std::snprintf(tail, sizeof tail, ": crc=%02x %s\n", crc, sp[8] == crc ? "YES" : "NO");
  char line2[32];
  std::snprintf(line2, sizeof line2, "t=%d\n", int(raw) * 1000 / 16);
  return bytes + tail + bytes + line2;
}

TEST(SimOneWire, HandFormatMatchesPrintfForEveryReading) {
  for (int raw = -55 * 16; raw <= 125 * 16; ++raw) {
    for (bool corrupt : {false, true}) {
      ASSERT_EQ(SimOneWire::formatW1Slave(std::int16_t(raw), corrupt),
                printfW1Slave(std::int16_t(raw), corrupt))
          << raw << (corrupt ? " corrupt" : "");
    }
  }
  EXPECT_EQ(SimOneWire::formatW1Slave(85 * 16, false), printfW1Slave(85 * 16, false));
}

}  // namespace
}  // namespace xr::sim
