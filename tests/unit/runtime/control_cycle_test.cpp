#include "runtime/control_cycle.h"

#include <gtest/gtest.h>

#include <array>
#include <initializer_list>

#include "fakes.h"

namespace xr::rt {
namespace {

using test::FakeClock;

struct CycleRig {
  CycleRig() : handoffs(Params{}), pwm(log), enable(log, 'E'), buzzer(log, 'B') {
    dev.sensors = &sensors;
    dev.pwm = &pwm;
    dev.fieldEnable = &enable;
    dev.buzzer = &buzzer;
    dev.watchdog = &watchdog;
    rebuild();
  }
  // A new cycle over the rig's devices and config, after a test changed them.
  void rebuild() { cycle = std::make_unique<ControlCycle>(core, dev, handoffs, stats, timing, cfg); }
  // The BMS and ignition lines, then a tick with each (bms, ignition) level
  // pair, checking what the core saw: charge enabled and ignition on.
  template <class Set>
  void expectDiscrete(DigitalInput& bms, DigitalInput& ign, Set&& set,
                      std::initializer_list<std::array<bool, 2>> seen) {
    dev.bms = &bms;
    dev.ignition = &ign;
    rebuild();
    int step = 0;
    for (const auto& want : seen) {
      set(step++);
      tick();
      EXPECT_EQ(core.lastInputs.bmsChargeEnabled, want[0]) << "step " << step - 1;
      EXPECT_EQ(core.lastInputs.ignitionOn, want[1]) << "step " << step - 1;
    }
  }
  bool tick() {
    clock.t += fromUs(2500);
    return cycle->tick(clock.t);
  }
  test::ScriptedCore core;
  Handoffs handoffs;
  LoopStats stats;
  FakeClock clock, timing;
  test::OutputLog log;
  test::FakeSensors sensors;
  test::FakePwm pwm;
  test::FakeDigitalOut enable, buzzer;
  test::FakeWatchdog watchdog;
  CycleDevices dev;
  CycleConfig cfg;
  std::unique_ptr<ControlCycle> cycle;
};

TEST(ControlCycle, WritesDutyBeforeRaisingEnable) {
  CycleRig r;
  r.core.requestDuty = 40.0;
  r.core.requestEnable = true;
  ASSERT_TRUE(r.tick());
  ASSERT_EQ(r.log.entries.size(), 3u);  // buzzer off, duty, enable
  std::string order;
  for (auto& e : r.log.entries) order += e.what;
  EXPECT_LT(order.find('D'), order.find('E'));
  EXPECT_DOUBLE_EQ(r.pwm.duty, 40.0);
  EXPECT_TRUE(r.enable.level);
}

TEST(ControlCycle, DropsEnableBeforeTheDutyWhenTurningOff) {
  CycleRig r;
  r.core.requestDuty = 40.0;
  r.core.requestEnable = true;
  r.tick();
  r.log.entries.clear();
  r.core.requestDuty = 0.0;
  r.core.requestEnable = false;
  r.tick();
  ASSERT_EQ(r.log.entries.size(), 2u);
  EXPECT_EQ(r.log.entries[0].what, 'E');
  EXPECT_EQ(r.log.entries[0].value, 0.0);
  EXPECT_EQ(r.log.entries[1].what, 'D');
}

TEST(ControlCycle, WritesOnlyOnChange) {
  CycleRig r;
  r.core.requestDuty = 25.0;
  r.core.requestEnable = true;
  r.tick();
  const auto n = r.log.entries.size();
  for (int i = 0; i < 5; ++i) r.tick();
  EXPECT_EQ(r.log.entries.size(), n);
}

TEST(ControlCycle, ClampsNonFiniteAndOutOfRangeDuty) {
  CycleRig r;
  r.core.requestEnable = true;
  r.core.requestDuty = 250.0;
  r.tick();
  EXPECT_DOUBLE_EQ(r.pwm.duty, 100.0);
  r.core.requestDuty = std::numeric_limits<double>::quiet_NaN();
  r.tick();
  EXPECT_DOUBLE_EQ(r.pwm.duty, 0.0);
}

TEST(ControlCycle, FeedsWatchdogOnlyAfterHealthyCycles) {
  CycleRig r;
  r.core.requestDuty = 30.0;
  r.core.requestEnable = true;
  r.tick();
  r.tick();
  EXPECT_EQ(r.watchdog.feeds, 2);
  r.pwm.fail = true;
  r.core.requestDuty = 35.0;  // forces a write, which fails
  EXPECT_FALSE(r.tick());
  EXPECT_EQ(r.watchdog.feeds, 2);
  EXPECT_EQ(r.cycle->health().outputWriteErrors, 1u);
}

TEST(ControlCycle, FailedPwmWriteDrivesEnableLow) {
  CycleRig r;
  r.core.requestDuty = 30.0;
  r.core.requestEnable = true;
  r.tick();
  ASSERT_TRUE(r.enable.level);
  r.pwm.fail = true;
  r.core.requestDuty = 60.0;
  r.tick();
  EXPECT_FALSE(r.enable.level);
}

TEST(ControlCycle, FailedEnableWriteIsNotHealthy) {
  CycleRig r;
  r.enable.fail = true;
  r.core.requestDuty = 30.0;
  r.core.requestEnable = true;
  EXPECT_FALSE(r.tick());
  EXPECT_EQ(r.watchdog.feeds, 0);
}

TEST(ControlCycle, SensorErrorIsCountedAndNotHealthyButOutputsStillWritten) {
  CycleRig r;
  r.sensors.ok = false;
  r.core.requestDuty = 10.0;
  r.core.requestEnable = true;
  EXPECT_FALSE(r.tick());
  EXPECT_EQ(r.cycle->health().sensorReadErrors, 1u);
  EXPECT_DOUBLE_EQ(r.pwm.duty, 10.0);
}

TEST(ControlCycle, AppliesQueuedCommandsAndParamsBetweenTicks) {
  CycleRig r;
  Command c;
  c.type = CommandType::Manual;
  c.value = 20;
  ASSERT_TRUE(r.handoffs.submitCommand(c));
  Params p;
  p.BulkVoltage = 14.1;
  r.handoffs.submitParams(p);
  r.tick();
  ASSERT_EQ(r.core.commands.size(), 1u);
  EXPECT_EQ(r.core.commands[0].type, CommandType::Manual);
  EXPECT_EQ(r.core.paramSets, 1);
  EXPECT_DOUBLE_EQ(r.core.params.BulkVoltage, 14.1);
  r.tick();
  EXPECT_EQ(r.core.paramSets, 1);  // only once per new value
  EXPECT_EQ(r.handoffs.latest().health.commandsApplied, 1u);
}

TEST(ControlCycle, RejectedCommandsAreCounted) {
  CycleRig r;
  r.core.rejectCommands = true;
  r.handoffs.submitCommand(Command{});
  r.tick();
  EXPECT_EQ(r.handoffs.latest().health.commandsRejected, 1u);
}

// the regulator's answer reaches the submitter.
TEST(ControlCycle, PostsTheRegulatorsAnswerForAcknowledgedCommands) {
  CycleRig r;
  const std::uint32_t applied = r.handoffs.submitCommandForAck(Command{});
  ASSERT_NE(applied, 0u);
  EXPECT_EQ(r.handoffs.acks.find(applied), -1);  // not before the tick
  r.tick();
  EXPECT_EQ(r.handoffs.acks.find(applied), 1);
  r.core.rejectCommands = true;
  const std::uint32_t refused = r.handoffs.submitCommandForAck(Command{});
  ASSERT_NE(refused, applied);
  r.tick();
  EXPECT_EQ(r.handoffs.acks.find(refused), 0);
  EXPECT_EQ(r.handoffs.acks.find(applied), 1);  // earlier answers stay readable
}

TEST(ControlCycle, AnAcknowledgementSlotIsNeverReadAsAnotherCommandsAnswer) {
  CycleRig r;
  const std::uint32_t first = r.handoffs.submitCommandForAck(Command{});
  r.tick();
  ASSERT_EQ(r.handoffs.acks.find(first), 1);
  r.core.rejectCommands = true;
  for (std::size_t i = 0; i < CommandAcks::kSlots; ++i) {
    ASSERT_NE(r.handoffs.submitCommandForAck(Command{}), 0u);
    r.tick();
  }
  EXPECT_EQ(r.handoffs.acks.find(first), -1);  // its slot now holds a later command: unknown, not "refused"
}

TEST(ControlCycle, BoundsCommandsPerTick) {
  CycleRig r;
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(r.handoffs.submitCommand(Command{}));
  r.tick();
  EXPECT_EQ(r.core.commands.size(), static_cast<std::size_t>(r.cfg.maxCommandsPerTick));
  r.tick();
  r.tick();
  EXPECT_EQ(r.core.commands.size(), 20u);
}

TEST(ControlCycle, SlowSensorFreshOnlyOnTheTickAfterANewSample) {
  CycleRig r;
  TemperatureHandoff t;
  t.tempF = 150.0;
  t.stamp = r.clock.t;
  t.heartbeat = r.clock.t;
  r.handoffs.temperature.store(t);
  r.tick();
  EXPECT_TRUE(r.core.lastInputs.AlternatorTemperatureF.fresh);
  EXPECT_DOUBLE_EQ(r.core.lastInputs.AlternatorTemperatureF.value, 150.0);
  EXPECT_EQ(r.core.lastInputs.tempTaskHeartbeat, t.heartbeat);
  r.tick();
  EXPECT_FALSE(r.core.lastInputs.AlternatorTemperatureF.fresh);
  EXPECT_DOUBLE_EQ(r.core.lastInputs.AlternatorTemperatureF.value, 150.0);  // latest value kept
  EXPECT_EQ(r.core.lastInputs.AlternatorTemperatureF.stamp, t.stamp);
}

TEST(ControlCycle, VictronSamplesReachTheInputs) {
  CycleRig r;
  VictronHandoff v;
  v.currentA = -12.5;
  v.voltageV = 13.1;
  v.solarW = 240;
  v.stamp = r.clock.t;
  r.handoffs.victron.store(v);
  r.tick();
  EXPECT_TRUE(r.core.lastInputs.VictronCurrent.fresh);
  EXPECT_DOUBLE_EQ(r.core.lastInputs.VictronCurrent.value, -12.5);
  EXPECT_DOUBLE_EQ(r.core.lastInputs.solarPowerW.value, 240);
}

TEST(ControlCycle, DiscreteInputErrorsReadAsTheSafeLevel) {
  CycleRig r;
  test::FakeDigitalIn bms, ign;
  r.expectDiscrete(bms, ign,
                   [&](int step) {
                     if (step == 0) bms.value = 0;  // BMS not asserting "charge disabled"
                     if (step == 1) {
                       bms.value = -1;  // read error
                       ign.value = 0;
                     }
                     if (step == 2) bms.value = 1;  // BMS asserts charge disabled
                   },
                   {{true, true}, {false, false}, {false, false}});
}

TEST(ControlCycle, PublishesSnapshotWithTelemetryAndTick) {
  CycleRig r;
  r.sensors.ibv = 13.7;
  r.tick();
  r.tick();
  const RuntimeSnapshot s = r.handoffs.latest();
  EXPECT_EQ(s.tick, 2u);
  EXPECT_DOUBLE_EQ(s.telemetry.ibv_v, 13.7);
  EXPECT_EQ(s.telemetry.now, r.clock.t);
}

TEST(ControlCycle, EventsGoToTheRingAndOverflowIsCounted) {
  CycleRig r;
  r.core.eventsPerTick = 10;
  for (int i = 0; i < 110; ++i) r.tick();  // 1100 events into a 1024 ring
  EXPECT_EQ(r.handoffs.events.dropped(), 1100u - EventRing::kCapacity);
  Event e;
  ASSERT_TRUE(r.handoffs.events.pop(e));
  EXPECT_DOUBLE_EQ(e.a, 1.0);  // oldest first
}

TEST(ControlCycle, RowsFollowTheTelemetryRate) {
  CycleRig r;
  r.cfg.rowPeriod = fromMs(100);
  r.rebuild();
  for (int i = 0; i < 400; ++i) r.tick();  // 1 s of 2.5 ms ticks
  EXPECT_EQ(r.handoffs.rows.size(), 10u);
}

TEST(ControlCycle, RowsAreDroppedAndCountedWhenTheWriterFallsBehind) {
  CycleRig r;
  r.cfg.rowPeriod = fromUs(2500);  // one per tick
  r.rebuild();
  const int ticks = static_cast<int>(decltype(r.handoffs.rows)::capacity()) + 5;
  for (int i = 0; i < ticks; ++i) r.tick();
  EXPECT_EQ(r.cycle->health().rowsDropped, 5u);
}

TEST(ControlCycle, ShutdownCommandsOffAndDriveSafeStateLowersEverything) {
  CycleRig r;
  r.core.requestDuty = 50.0;
  r.core.requestEnable = true;
  r.core.requestBuzzer = true;
  r.tick();
  EXPECT_FALSE(r.cycle->fieldIsOff());
  r.cycle->beginShutdown();
  ASSERT_FALSE(r.core.commands.empty());
  EXPECT_EQ(r.core.commands.back().type, CommandType::Off);
  for (int i = 0; i < 10 && !r.cycle->fieldIsOff(); ++i) r.tick();
  EXPECT_TRUE(r.cycle->fieldIsOff());
  r.cycle->driveSafeState();
  EXPECT_FALSE(r.enable.level);
  EXPECT_DOUBLE_EQ(r.pwm.duty, 0.0);
  EXPECT_FALSE(r.buzzer.level);
}

TEST(ControlCycle, SampleRatesCountFreshSamples) {
  CycleRig r;
  for (int i = 0; i < 801; ++i) r.tick();  // 2 s at 400 Hz
  const LoopStatsSummary s = r.stats.summary();
  EXPECT_NEAR(s.ch1SampleRateHz, 400.0, 1.0);      // fresh every tick
  EXPECT_NEAR(s.adsChannelRateHz[0], 100.0, 1.0);  // fresh every 4th tick
  EXPECT_NEAR(s.inaSampleRateHz, 400.0, 1.0);
}

TEST(ControlCycle, ServicesReadyEdgesUntilTheDeadlineAndCountsEverySample) {
  CycleRig r;
  test::FakeEdges edges(r.clock.t);
  r.dev.adsReady = &edges;
  r.sensors.counting = true;
  r.rebuild();
  TimeNs next = r.clock.t;
  for (int i = 0; i < 801; ++i) {  // 2 s at 400 Hz, as ControlLoop does it
    next += fromUs(2500);
    r.cycle->serviceEdges(next);
    r.clock.t = next;
    r.cycle->tick(next);
  }
  // 860 edges per second, each handed to the sensors with its own stamp, all
  // before the deadline they were waited against.
  ASSERT_GE(r.sensors.edges.size(), 1715u);
  EXPECT_LE(r.sensors.edges.size(), 1722u);
  for (std::size_t i = 1; i < r.sensors.edges.size(); ++i)
    EXPECT_EQ(r.sensors.edges[i] - r.sensors.edges[i - 1], edges.period);
  const LoopStatsSummary s = r.stats.summary();
  // Two results in one tick count twice: the rate is the chip's, not the tick's.
  EXPECT_NEAR(s.ch1SampleRateHz, 860.0, 3.0);
  EXPECT_EQ(s.adsEdges, r.sensors.edges.size());
}

TEST(ControlCycle, WithoutAReadyLineNoEdgeIsWaitedFor) {
  CycleRig r;
  r.cycle->serviceEdges(r.clock.t + fromUs(2500));
  EXPECT_TRUE(r.sensors.edges.empty());
  EXPECT_EQ(r.stats.summary().adsEdges, 0u);
}

TEST(ControlCycle, EdgeErrorsAreCountedAndDoNotBlockTheTick) {
  CycleRig r;
  test::FakeEdges edges(r.clock.t);
  edges.fail = true;
  r.dev.adsReady = &edges;
  r.rebuild();
  r.cycle->serviceEdges(r.clock.t + fromUs(2500));
  EXPECT_EQ(edges.waits, 1);
  EXPECT_EQ(r.cycle->health().edgeErrors, 1u);
  EXPECT_TRUE(r.tick());
}

TEST(ControlCycle, AnEdgeStormCannotStarveTheTick) {
  CycleRig r;
  test::FakeEdges edges(r.clock.t);
  edges.period = 1;  // a noisy line: an edge every nanosecond
  r.dev.adsReady = &edges;
  r.rebuild();
  r.cycle->serviceEdges(r.clock.t + fromUs(2500));
  EXPECT_EQ(r.sensors.edges.size(), 16u);  // bounded per period
}

// A clock that counts its reads: the cycle reads its timing clock only on
// timed ticks.
class CountingClock final : public Clock {
 public:
  TimeNs now() const noexcept override {
    ++reads;
    return 0;
  }
  void sleepUntil(TimeNs) noexcept override {}
  mutable int reads = 0;
};

// Counts the periodic ledger copies.
class LedgerCore final : public ControlCore {
 public:
  explicit LedgerCore(ControlCore& inner) : inner_(inner) {}
  const Outputs& step(const Inputs& in) override { return inner_.step(in); }
  void setParams(const Params& p) override { inner_.setParams(p); }
  bool command(const Command& c) override { return inner_.command(c); }
  bool ledger(BatteryLedger&) override {
    ++ledgers;
    return false;
  }
  int ledgers = 0;

 private:
  ControlCore& inner_;
};

TEST(ControlCycle, ThinnedRunTimesStoresAndCopiesTheLedgerOnTheirTicks) {
  // Each extra falls on the ticks numbered (from 0) by multiples of its
  // period: timed when (ticks before) % timeEveryTicks == 0, snapshot stored
  // when (ticks after) % publishEveryTicks == 1, ledger when (ticks after) %
  // 100 == 1, loop summary refreshed when (ticks after) % 64 == 1.
  CycleRig r;
  CountingClock timing;
  LedgerCore core(r.core);
  CycleConfig cfg;
  cfg.rowPeriod = 0;
  cfg.thinForUnpacedRun();
  ASSERT_EQ(cfg.publishEveryTicks, 40);
  ASSERT_EQ(cfg.timeEveryTicks, 16);
  ControlCycle cycle(core, r.dev, r.handoffs, r.stats, timing, cfg);
  std::uint64_t lastStored = 0, lastSummary = 0;
  for (std::uint64_t k = 1; k <= 1000; ++k) {
    const int readsBefore = timing.reads;
    const int ledgersBefore = core.ledgers;
    r.clock.t += fromUs(2500);
    cycle.tick(r.clock.t);
    EXPECT_EQ(timing.reads - readsBefore, (k - 1) % 16 == 0 ? 4 : 0) << "tick " << k;
    EXPECT_EQ(core.ledgers - ledgersBefore, k % 100 == 1 ? 1 : 0) << "tick " << k;
    if (k % 40 == 1) lastStored = k;
    if (k % 64 == 1) lastSummary = k;
    const RuntimeSnapshot snap = r.handoffs.snapshot.load();
    EXPECT_EQ(snap.tick, lastStored) << "tick " << k;
    // The stored snapshot carries the summary as last refreshed (after that
    // tick was counted), not a fresher one.
    if (k == lastStored) {
      EXPECT_EQ(snap.loop.ticks, lastSummary) << "tick " << k;
    }
  }
}

// A core whose telemetry names the tick it was computed on (target_v).
class StampingCore final : public ControlCore {
 public:
  explicit StampingCore(test::ScriptedCore& inner) : inner_(inner) {}
  const Outputs& step(const Inputs& in) override {
    out_ = inner_.step(in);
    out_.telemetry.target_v = inner_.steps;
    return out_;
  }
  void setParams(const Params& p) override { inner_.setParams(p); }
  bool command(const Command& c) override { return inner_.command(c); }

 private:
  test::ScriptedCore& inner_;
  Outputs out_;
};

TEST(ControlCycle, ThinnedRunStoresAndRowsCarryTheirOwnTicksTelemetry) {
  // Every stored snapshot and row carries the telemetry of the tick it names,
  // and the final publish stores the last tick even when thinning skipped it.
  CycleRig r;
  StampingCore core(r.core);
  CycleConfig cfg;
  cfg.rowPeriod = fromMs(250);  // every 100th tick, not on the publish phase
  cfg.thinForUnpacedRun();
  ControlCycle cycle(core, r.dev, r.handoffs, r.stats, r.timing, cfg);
  int rows = 0, stores = 0;
  std::uint64_t lastStored = 0;
  for (std::uint64_t k = 1; k <= 1003; ++k) {
    r.clock.t += fromUs(2500);
    cycle.tick(r.clock.t);
    const RuntimeSnapshot snap = r.handoffs.snapshot.load();
    if (snap.tick != lastStored) {
      ++stores;
      lastStored = snap.tick;
    }
    EXPECT_EQ(snap.telemetry.target_v, static_cast<double>(snap.tick)) << "tick " << k;
    RuntimeSnapshot row;
    while (r.handoffs.rows.pop(row)) {
      ++rows;
      EXPECT_EQ(row.tick, k);
      EXPECT_EQ(row.telemetry.target_v, static_cast<double>(k));
    }
  }
  EXPECT_GE(rows, 10);
  EXPECT_GE(stores, 25);
  EXPECT_LT(stores, 1003);  // thinned
  cycle.publishLatest();
  const RuntimeSnapshot last = r.handoffs.snapshot.load();
  EXPECT_EQ(last.tick, 1003u);
  EXPECT_EQ(last.telemetry.target_v, 1003.0);
}

}  // namespace
}  // namespace xr::rt
