// DriverSensors (runtime/driver_sensors.h) against the simulated board: ready-edge
// pacing uses every conversion; a configured ALERT/RDY line that never
// pulses falls back to single-shot pacing instead of starving the regulator.
#include <gtest/gtest.h>

#include "drivers/sim/sim_clock.h"
#include "drivers/sim/sim_world.h"
#include "runtime/driver_sensors.h"
#include "sim_rig/sim_ready_edges.h"

namespace xr {
namespace {

struct Board {
  explicit Board(bool readyEdges)
      : world(sim::WorldConfig{}, hw),
        clock(world, 0.0),
        sensors(world.i2c(), hw, clock, readyEdges),
        edges(world) {
    world.advanceTo(fromMs(100));  // powered before the daemon starts
    const auto r = sensors.start(world.now(), 14.7);
    EXPECT_EQ(r.inaError, 0);
    EXPECT_EQ(r.adsError, 0);
  }
  // One 2.5 ms control period: edges first (when delivered), then the tick.
  void period(bool deliverEdges) {
    const TimeNs deadline = world.now() + fromUs(2500);
    TimeNs stamp = 0;
    for (int i = 0; deliverEdges && i < 16 && edges.waitEdge(deadline, &stamp) == 1; ++i)
      sensors.onReadyEdge(stamp);
    world.advanceTo(deadline);
    sensors.read(world.now(), in);
  }
  std::uint32_t ch1() const { return sensors.sampleCounts()->ads[1]; }
  HardwareSettings hw;
  sim::SimWorld world;
  sim::SimClock clock;
  DriverSensors sensors;
  sim::SimReadyEdges edges;
  Inputs in;
};

TEST(DriverSensors, ReadyEdgesUseEveryConversion) {
  Board b(true);
  for (int i = 0; i < 400; ++i) b.period(true);  // 1 s
  // Sequence {1,0,1,2,1,3}: half of ~860 conversions are CH1, minus the two
  // results discarded while the pipeline fills.
  EXPECT_GE(b.ch1(), 420u);
  EXPECT_LE(b.ch1(), 431u);
  EXPECT_FALSE(b.sensors.edgeFallback());
  EXPECT_EQ(b.sensors.ads().stats().pipelineFlushes, 0u);
  EXPECT_TRUE(b.in.altCurrentRaw.fresh || b.in.altCurrentRaw.stamp > 0);
}

TEST(DriverSensors, SilentReadyLineFallsBackToSingleShot) {
  Board b(true);
  // 240 ms without an edge: still waiting (no sample yet, no fallback).
  for (int i = 0; i < 96; ++i) b.period(false);
  EXPECT_FALSE(b.sensors.edgeFallback());
  EXPECT_EQ(b.ch1(), 0u);
  // Past kEdgeSilence (250 ms): one restart in ready mode, no fallback yet.
  for (int i = 0; i < 8; ++i) b.period(false);
  EXPECT_FALSE(b.sensors.edgeFallback());
  EXPECT_EQ(b.sensors.ads().pacing(), AdsPacing::ReadyEdge);
  // Silent for another 250 ms: single-shot takes over.
  for (int i = 0; i < 100; ++i) b.period(false);
  EXPECT_TRUE(b.sensors.edgeFallback());
  EXPECT_EQ(b.sensors.ads().pacing(), AdsPacing::SingleShot);
  ASSERT_NE(b.sensors.sampleCounts(), nullptr);
  EXPECT_TRUE(b.sensors.sampleCounts()->readyEdgeFallback);
  const std::uint32_t before = b.ch1();
  for (int i = 0; i < 400; ++i) b.period(false);  // 1 s of single-shot pacing
  EXPECT_GE(b.ch1() - before, 190u);              // one conversion per tick, CH1 every other
  EXPECT_TRUE(b.in.altCurrentRaw.stamp > 0);
}

TEST(DriverSensors, NotWiredUsesSingleShotFromTheStart) {
  Board b(false);
  for (int i = 0; i < 400; ++i) b.period(false);
  EXPECT_GE(b.ch1(), 190u);
  EXPECT_LE(b.ch1(), 201u);
  EXPECT_FALSE(b.sensors.edgeFallback());
}

TEST(DriverSensors, AChipResetThatStopsTheEdgesIsRestartedNotAbandoned) {
  Board b(true);
  for (int i = 0; i < 40; ++i) b.period(true);
  // Power glitch: the ADS1115 comes back with its reset Config (single-shot,
  // comparator off), so ALERT/RDY stops pulsing although the chip answers.
  std::uint8_t reset[3] = {0x01, 0x85, 0x83};
  I2cMsg m{b.hw.ads1115_address, false, reset, 3};
  ASSERT_EQ(b.world.i2c().transfer(std::span<I2cMsg>(&m, 1)), 0);
  for (int i = 0; i < 400; ++i) b.period(true);
  EXPECT_FALSE(b.sensors.edgeFallback());
  EXPECT_EQ(b.sensors.ads().pacing(), AdsPacing::ReadyEdge);
  const std::uint32_t before = b.ch1();
  for (int i = 0; i < 400; ++i) b.period(true);
  EXPECT_GE(b.ch1() - before, 420u);  // back to every conversion
}

}  // namespace
}  // namespace xr
