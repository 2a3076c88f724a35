// VE.Direct handed to the control thread once (docs/architecture.md
// "Threads"), as the DS18B20 is: the reader's thread posts each new block
// into Handoffs::victron (postVeDirect, the board's sink), and the control
// cycle reads that one hand-off. No tick hook runs here: nothing on the
// control thread copies the reader's own sample.
#include "runtime/vedirect_handoff.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include "fakes.h"
#include "runtime/control_cycle.h"
#include "vedirect_pty.h"

namespace xr::rt {
namespace {

struct Rig {
  Rig() : handoffs(Params{}), pwm(log), enable(log, 'E') {
    dev.sensors = &sensors;
    dev.pwm = &pwm;
    dev.fieldEnable = &enable;
    cycle = std::make_unique<ControlCycle>(core, dev, handoffs, stats, timing);
  }
  void tick() {
    clock.t += fromUs(2500);
    cycle->tick(clock.t);
  }
  test::ScriptedCore core;
  Handoffs handoffs;
  LoopStats stats;
  test::FakeClock clock, timing;
  test::OutputLog log;
  test::FakeSensors sensors;
  test::FakePwm pwm;
  test::FakeDigitalOut enable;
  CycleDevices dev;
  std::unique_ptr<ControlCycle> cycle;
};

template <typename Pred>
bool waitFor(Pred p) {
  // Bounded wait for the reader thread; no duration is asserted.
  for (int i = 0; i < 5000 && !p(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return p();
}

TEST(VeDirectHandoff, TheControlThreadReadsTheBlockFromTheReadersOneHandoff) {
  Rig r;
  xr::test::Pty pty;
  ASSERT_FALSE(pty.slave().empty());
  VeDirectReader reader(pty.slave(), {}, 50'000'000);
  std::atomic<int> posts{0};
  reader.onSample([&](const VeDirectSample& s) {
    postVeDirect(r.handoffs, s);
    ++posts;
  });
  reader.start();
  ASSERT_TRUE(waitFor([&] { return reader.latest().portOpen; }));
  ASSERT_TRUE(pty.write(xr::test::block(xr::test::kFields) + xr::test::block(xr::test::kFields)));
  ASSERT_TRUE(waitFor([&] { return posts.load() >= 1; }));
  r.tick();
  const Inputs& in = r.core.lastInputs;
  EXPECT_TRUE(in.VictronCurrent.fresh);
  EXPECT_DOUBLE_EQ(in.VictronCurrent.value, -1.5);
  EXPECT_DOUBLE_EQ(in.VictronVoltage.value, 13.25);
  EXPECT_DOUBLE_EQ(in.solarPowerW.value, 120.0);
  EXPECT_EQ(in.VictronCurrent.stamp, reader.latest().stamp) << "the reader's own stamp, not the tick's";
  r.tick();
  EXPECT_FALSE(r.core.lastInputs.VictronCurrent.fresh) << "no new block: the same reading, not fresh";
  EXPECT_DOUBLE_EQ(r.core.lastInputs.VictronCurrent.value, -1.5);

  ASSERT_TRUE(pty.write(xr::test::block({{"V", "12000"}, {"I", "2500"}, {"PPV", "80"}})));
  ASSERT_TRUE(waitFor([&] { return posts.load() >= 2; }));
  r.tick();
  EXPECT_TRUE(r.core.lastInputs.VictronCurrent.fresh);
  EXPECT_DOUBLE_EQ(r.core.lastInputs.VictronCurrent.value, 2.5);
  EXPECT_DOUBLE_EQ(r.core.lastInputs.VictronVoltage.value, 12.0);
  reader.stop();
}

TEST(VeDirectHandoff, NothingIsPostedBeforeTheDeviceSentACurrent) {
  Handoffs h{Params{}};
  VeDirectSample s;
  s.hasVoltage = true;
  s.voltageV = 13.0;
  s.stamp = 5;
  s.frames = 1;
  const std::uint64_t before = h.victron.version();
  postVeDirect(h, s);
  EXPECT_EQ(h.victron.version(), before);
  s.hasCurrent = true;
  s.currentA = 4.0;
  postVeDirect(h, s);
  VictronHandoff v;
  h.victron.load(v);
  EXPECT_DOUBLE_EQ(v.currentA, 4.0);
  EXPECT_DOUBLE_EQ(v.voltageV, 13.0);
  EXPECT_TRUE(std::isnan(v.solarW)) << "no PPV sent: no value, not 0 W";
  EXPECT_EQ(v.stamp, 5);
}

}  // namespace
}  // namespace xr::rt
