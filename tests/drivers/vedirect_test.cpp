// VE.Direct: the block parser (checksum, labels, garbage, HEX interleaving)
// and the reader thread on a pseudo-terminal (good frames, bad checksums,
// garbage, unplug).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "drivers/vedirect/vedirect_parser.h"
#include "drivers/vedirect/vedirect_reader.h"
#include "vedirect_pty.h"

namespace xr {
namespace {

using test::block;
using test::kFields;
using test::Pty;

struct Collect {
  std::vector<vedirect::Frame> frames;
  static void cb(void* ctx, const vedirect::Frame& f) { static_cast<Collect*>(ctx)->frames.push_back(f); }
};

TEST(VeDirectParser, FirstBlockOnlySynchronises) {
  vedirect::Parser p;
  Collect c;
  // Starting mid-stream the first block's boundary is unknown: not counted.
  EXPECT_EQ(p.feed(block(kFields), &Collect::cb, &c), 0u);
  EXPECT_EQ(p.feed(block(kFields), &Collect::cb, &c), 1u);
  ASSERT_EQ(c.frames.size(), 1u);
  const auto& f = c.frames[0];
  EXPECT_TRUE(f.hasV && f.hasI && f.hasPPV);
  EXPECT_DOUBLE_EQ(f.voltageV, 13.25);
  EXPECT_DOUBLE_EQ(f.currentA, -1.5);
  EXPECT_DOUBLE_EQ(f.ppvW, 120.0);
  EXPECT_DOUBLE_EQ(f.panelV, 36.01);
  EXPECT_EQ(f.chargeState, 3);
}

TEST(VeDirectParser, BadChecksumIsDroppedAndCounted) {
  vedirect::Parser p;
  Collect c;
  p.feed(block(kFields), &Collect::cb, &c);
  EXPECT_EQ(p.feed(block(kFields, 1), &Collect::cb, &c), 0u);
  EXPECT_EQ(p.badChecksums(), 1u);
  EXPECT_EQ(p.feed(block(kFields), &Collect::cb, &c), 1u) << "recovers on the next block";
}

TEST(VeDirectParser, ByteByByteEqualsWhole) {
  vedirect::Parser p;
  Collect c;
  const std::string s = block(kFields) + block(kFields) + block({{"V", "12000"}});
  for (char ch : s) p.feed(std::string_view(&ch, 1), &Collect::cb, &c);
  ASSERT_EQ(c.frames.size(), 2u);
  EXPECT_DOUBLE_EQ(c.frames[1].voltageV, 12.0);
  EXPECT_FALSE(c.frames[1].hasI);
}

TEST(VeDirectParser, GarbageIsSurvivedAndTheStreamRecovers) {
  vedirect::Parser p;
  Collect c;
  std::string junk;
  unsigned x = 12345;
  for (int i = 0; i < 5000; ++i) {
    x = x * 1103515245u + 12345u;
    junk += static_cast<char>((x >> 16) & 0xFF);
  }
  p.feed(junk, &Collect::cb, &c);
  // Random bytes can pass a mod-256 checksum by chance, but never with a
  // non-numeric V/I/PPV; what matters: it recovers.
  c.frames.clear();
  p.feed(block(kFields) + block(kFields), &Collect::cb, &c);
  ASSERT_GE(c.frames.size(), 1u);
  EXPECT_DOUBLE_EQ(c.frames.back().voltageV, 13.25);
}

TEST(VeDirectParser, NonNumericValueForAKnownLabelIsMalformed) {
  vedirect::Parser p;
  Collect c;
  p.feed(block(kFields), &Collect::cb, &c);
  EXPECT_EQ(p.feed(block({{"V", "12x00"}}), &Collect::cb, &c), 0u);
  EXPECT_EQ(p.malformed(), 1u);
}

TEST(VeDirectParser, HexMessagesInterleavedAreSkipped) {
  vedirect::Parser p;
  Collect c;
  p.feed(block(kFields), &Collect::cb, &c);
  std::string b = block(kFields);
  b.insert(10, ":A0102000543\n");
  EXPECT_EQ(p.feed(b, &Collect::cb, &c), 1u);
  EXPECT_EQ(p.badChecksums(), 0u);
}

template <typename Pred>
bool waitFor(Pred p) {
  // Bounded wait for the reader thread; no duration is asserted.
  for (int i = 0; i < 5000; ++i) {
    if (p()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return p();
}

TEST(VeDirectReader, ReadsFramesFromAPseudoTerminal) {
  Pty pty;
  ASSERT_FALSE(pty.slave().empty());
  VeDirectReader r(pty.slave(), {}, 50'000'000);
  r.start();
  ASSERT_TRUE(waitFor([&] { return r.latest().portOpen; }));
  ASSERT_TRUE(pty.write(block(kFields) + block(kFields) + block(kFields, 7) + "\x01\x02garbage\r\n" +
                        block(kFields) + block({{"V", "13000"}, {"I", "2500"}, {"PPV", "80"}})));
  ASSERT_TRUE(waitFor([&] { return r.latest().frames >= 2; }));
  const auto s = r.latest();
  EXPECT_GE(s.badChecksums, 1u);
  EXPECT_TRUE(s.hasCurrent && s.hasVoltage && s.hasPpv);
  EXPECT_DOUBLE_EQ(s.voltageV, 13.0);
  EXPECT_DOUBLE_EQ(s.currentA, 2.5);
  EXPECT_DOUBLE_EQ(s.ppvW, 80.0);
  EXPECT_GT(s.stamp, 0);
  r.stop();
}

TEST(VeDirectReader, UnplugClosesThePortAndKeepsTheLastStamp) {
  Pty pty;
  VeDirectReader r(pty.slave(), {}, 50'000'000);
  r.start();
  ASSERT_TRUE(waitFor([&] { return r.latest().portOpen; }));
  pty.write(block(kFields) + block(kFields));
  ASSERT_TRUE(waitFor([&] { return r.latest().frames >= 1; }));
  const TimeNs stamp = r.latest().stamp;
  pty.closeMaster();  // the cable is pulled
  ASSERT_TRUE(waitFor([&] { return !r.latest().portOpen; }));
  EXPECT_EQ(r.latest().stamp, stamp) << "no new data: the consumer sees it go stale";
  r.stop();
}

TEST(VeDirectReader, TheSinkGetsEachNewBlockOnceOnTheReadersThread) {
  Pty pty;
  VeDirectReader r(pty.slave(), {}, 50'000'000);
  std::atomic<int> calls{0};
  std::atomic<bool> onReaderThread{true};
  std::atomic<bool> latestHadIt{true};
  const auto testThread = std::this_thread::get_id();
  r.onSample([&](const VeDirectSample& s) {
    if (std::this_thread::get_id() == testThread) onReaderThread = false;
    if (r.latest().frames != s.frames) latestHadIt = false;
    ++calls;
  });
  r.start();
  ASSERT_TRUE(waitFor([&] { return r.latest().portOpen; }));
  ASSERT_TRUE(pty.write(block(kFields) + block(kFields)));  // the first block only synchronises
  ASSERT_TRUE(waitFor([&] { return calls.load() >= 1; }));
  ASSERT_TRUE(pty.write(block(kFields, 3)));  // a bad checksum: no new block, no call
  ASSERT_TRUE(pty.write(block({{"V", "12500"}, {"I", "800"}})));
  ASSERT_TRUE(waitFor([&] { return calls.load() >= 2; }));
  r.stop();
  EXPECT_EQ(calls.load(), 2);
  EXPECT_EQ(r.latest().frames, 2u);
  EXPECT_TRUE(onReaderThread.load());
  EXPECT_TRUE(latestHadIt.load()) << "latest() has the block before the sink is told";
}

TEST(VeDirectReader, MissingPortStaysClosedAndStopsPromptly) {
  VeDirectReader r("/dev/ttyDOES-NOT-EXIST", {}, 10'000'000);
  r.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_FALSE(r.latest().portOpen);
  EXPECT_EQ(r.latest().frames, 0u);
  r.stop();
}

TEST(VeDirectTty, RejectsANonTerminal) { EXPECT_NE(configureVeDirectTty(::open("/dev/null", O_RDONLY)), 0); }

}  // namespace
}  // namespace xr
