#include "runtime/control_loop.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "fakes.h"
#include "loop_rig.h"
#include "runtime/monotonic_clock.h"

namespace xr::rt {
namespace {

using test::FakeClock;

TEST(ControlLoop, RunsForTheDurationOnAbsoluteDeadlines) {
  test::LoopRig r;
  LoopConfig cfg;
  cfg.period = fromUs(2500);
  cfg.duration = fromSec(1.0);
  ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
  const TimeNs start = r.clock.t;
  EXPECT_EQ(loop.run(), LoopExit::DurationReached);
  EXPECT_EQ(r.core.steps, 400);
  EXPECT_EQ(loop.heartbeat(), 400u);
  EXPECT_EQ(r.clock.t, start + fromUs(2500) * 399);  // last deadline slept to
  EXPECT_TRUE(loop.finished());
  EXPECT_EQ(r.stats.summary().overruns, 0u);
}

TEST(ControlLoop, LeavesTheFieldSafeAtTheEnd) {
  test::LoopRig r;
  r.core.requestDuty = 60.0;
  r.core.requestEnable = true;
  LoopConfig cfg;
  cfg.duration = fromMs(100);
  ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
  loop.run();
  EXPECT_FALSE(r.enable.level);
  EXPECT_DOUBLE_EQ(r.pwm.duty, 0.0);
}

TEST(ControlLoop, StopRunsTheControlledRampBeforeForcingOff) {
  test::LoopRig r;
  r.core.requestDuty = 50.0;
  r.core.requestEnable = true;
  r.core.rampStep = 10.0;  // 5 ticks to reach 0
  LoopConfig cfg;
  ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
  int stepsAtStop = -1;
  r.core.onStep = [&](const Inputs&) {
    if (r.core.steps == 20) {
      loop.requestStop();
      stepsAtStop = r.core.steps;
    }
  };
  EXPECT_EQ(loop.run(), LoopExit::Stopped);
  ASSERT_EQ(stepsAtStop, 20);
  // Ramp: 40, 30, 20, 10, 0 written before the loop ended on its own.
  EXPECT_EQ(r.core.steps, 25);
  std::vector<double> duties;
  for (auto& e : r.log.entries)
    if (e.what == 'D') duties.push_back(e.value);
  ASSERT_GE(duties.size(), 6u);
  EXPECT_DOUBLE_EQ(duties[1], 40.0);
  EXPECT_DOUBLE_EQ(duties[4], 10.0);
  EXPECT_FALSE(r.enable.level);
  EXPECT_DOUBLE_EQ(r.pwm.duty, 0.0);
}

TEST(ControlLoop, StopForcesTheFieldOffWhenTheRampDoesNotFinishInBudget) {
  test::LoopRig r;
  r.core.requestDuty = 50.0;
  r.core.requestEnable = true;
  r.core.rampStep = 0.0;  // a core that never ramps down
  LoopConfig cfg;
  cfg.shutdownBudget = fromMs(500);
  ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
  r.core.onStep = [&](const Inputs&) {
    if (r.core.steps == 10) loop.requestStop();
  };
  const TimeNs start = r.clock.t;
  loop.run();
  EXPECT_FALSE(r.enable.level);
  EXPECT_DOUBLE_EQ(r.pwm.duty, 0.0);
  // Ended about one budget after the stop, well inside 3 s.
  EXPECT_LE(r.clock.t - start, fromMs(25) + fromMs(500) + fromUs(2500));
}

TEST(ControlLoop, DetectsAndSkipsOverruns) {
  test::LoopRig r;
  LoopConfig cfg;
  cfg.period = fromUs(2500);
  cfg.duration = fromMs(100);  // 40 deadlines
  ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
  r.core.onStep = [&](const Inputs&) {
    if (r.core.steps == 10) r.clock.t += fromUs(2500) * 3 + fromUs(100);  // a 7.6 ms stall
  };
  loop.run();
  // Deadlines 11 and 12 passed entirely during the stall and are skipped;
  // deadline 13 runs 100 µs late.
  EXPECT_EQ(r.stats.summary().overruns, 2u);
  EXPECT_EQ(r.stats.summary().overrunsOwn, 2u);  // the tick itself stalled
  EXPECT_EQ(r.core.steps, 40 - 2);
}

TEST(ControlLoop, SmallLatenessIsNotAnOverrun) {
  test::LoopRig r;
  LoopConfig cfg;
  cfg.duration = fromMs(50);
  ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
  r.core.onStep = [&](const Inputs&) { r.clock.t += fromUs(2600); };  // each tick overruns its slot a bit
  loop.run();
  EXPECT_EQ(r.stats.summary().overruns, 0u);
}

TEST(ControlLoop, MeasuresPeriodErrorAgainstTheWallDeadline) {
  test::LoopRig r;
  FakeClock wall;
  LoopConfig cfg;
  cfg.duration = fromMs(25);  // 10 ticks
  cfg.wall = &wall;
  cfg.wallDeadlineOf = [&](TimeNs t) { return t - r.clock.t + wall.t - fromUs(120); };  // always 120 µs late
  ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
  loop.run();
  const auto s = r.stats.summary();
  EXPECT_TRUE(s.periodMeasured);
  EXPECT_DOUBLE_EQ(s.periodErrMaxUs, 120.0);
  EXPECT_DOUBLE_EQ(s.periodErrP99Us, 120.0);
  EXPECT_EQ(s.periodErrHist[2], 0u);   // none under 100 µs
  EXPECT_EQ(s.periodErrHist[3], 10u);  // all under 200 µs
}

TEST(ControlLoop, StopRequestedBeforeRunStillLeavesFieldSafe) {
  test::LoopRig r;
  ControlLoop loop(*r.cycle, r.clock, r.stats, LoopConfig{});
  loop.requestStop();
  EXPECT_EQ(loop.run(), LoopExit::Stopped);
  EXPECT_FALSE(r.enable.level);
  EXPECT_DOUBLE_EQ(r.pwm.duty, 0.0);
}

}  // namespace
}  // namespace xr::rt

namespace xr::rt {
namespace {

TEST(PacedClock, AnchorsAtTheFirstDeadlineAndScalesBySpeed) {
  test::FakeClock virt, wall;
  PacedClock paced(virt, wall, 10.0);
  wall.t += fromSec(5.0);  // start-up time before the loop: not lateness
  const TimeNs v0 = virt.t + fromMs(1);
  paced.sleepUntil(v0);
  EXPECT_EQ(virt.t, v0);
  const TimeNs w0 = wall.t;
  paced.sleepUntil(v0 + fromSec(1.0));  // one virtual second = 100 ms of wall at 10x
  EXPECT_EQ(wall.t, w0 + fromMs(100));
  EXPECT_EQ(paced.wallDeadline(v0 + fromSec(2.0)), w0 + fromMs(200));
}

struct CountingHook final : TickHook {
  void beforeTick(TimeNs now) override {
    ++calls;
    last = now;
    if (throwAt > 0 && calls == throwAt) throw std::runtime_error("hook failure");
  }
  int calls = 0;
  int throwAt = 0;
  TimeNs last = 0;
};

TEST(ControlLoop, RunsTheTickHookFirstAndLetsItsExceptionOut) {
  test::LoopRig r;
  CountingHook hook;
  hook.throwAt = 5;
  r.dev.hook = &hook;
  r.core.requestDuty = 30.0;
  r.core.requestEnable = true;
  r.cycle = std::make_unique<ControlCycle>(r.core, r.dev, r.handoffs, r.stats, r.clock, CycleConfig{});
  ControlLoop loop(*r.cycle, r.clock, r.stats, LoopConfig{});
  EXPECT_THROW(loop.run(), std::runtime_error);
  EXPECT_EQ(hook.calls, 5);
  EXPECT_EQ(r.core.steps, 4);  // the hook runs before the step of its tick
  // The daemon drives the safe state on this path; the cycle can do it.
  r.cycle->driveSafeState();
  EXPECT_FALSE(r.enable.level);
}

}  // namespace
}  // namespace xr::rt

namespace xr::rt {
namespace {

TEST(ControlLoop, PacedSimulationJudgesOverrunsOnTheWallClock) {
  test::LoopRig r;
  FakeClock wall;
  LoopConfig cfg;
  cfg.duration = fromMs(100);  // 40 deadlines
  cfg.wall = &wall;
  const TimeNs virt0 = r.clock.t, wall0 = wall.t;
  cfg.wallDeadlineOf = [&](TimeNs t) { return wall0 + (t - virt0); };  // speed 1
  r.core.onStep = [&](const Inputs&) {
    wall.t = cfg.wallDeadlineOf(r.clock.t);                            // on time...
    if (r.core.steps == 10) wall.t += fromUs(2500) * 3 + fromUs(100);  // ...except one 7.6 ms wall stall
  };
  ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
  loop.run();
  EXPECT_EQ(r.stats.summary().overruns, 2u);  // the virtual clock alone would see none
  EXPECT_EQ(r.stats.summary().overrunsOwn, 2u);
  EXPECT_EQ(r.core.steps, 38);
}

TEST(ControlLoop, ALateWakeUpIsAnOverrunButNotTheDaemons) {
  test::LoopRig r;
  test::JumpingWall wall;
  LoopConfig cfg;
  cfg.duration = fromMs(100);  // 40 deadlines
  cfg.wall = &wall;
  const TimeNs virt0 = r.clock.t, wall0 = wall.t;
  cfg.wallDeadlineOf = [&](TimeNs t) { return wall0 + (t - virt0); };  // speed 1
  r.core.onStep = [&](const Inputs&) {
    wall.t = std::max(wall.t, cfg.wallDeadlineOf(r.clock.t));  // each tick takes no wall time
    if (r.core.steps == 10) {
      // After this tick's overrun check, the next wake-up comes 10.1 ms after
      // this deadline: 7.6 ms late, deadlines 12 and 13 are missed.
      wall.jump = fromUs(2500) * 4 + fromUs(100);
      wall.jumpInReads = 1;
    }
  };
  ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
  loop.run();
  EXPECT_EQ(r.stats.summary().overruns, 2u);
  EXPECT_EQ(r.stats.summary().overrunsOwn, 0u);
}

}  // namespace
}  // namespace xr::rt

namespace xr::rt {
namespace {

TEST(ControlLoop, AbortEndsWithoutTheRampAndLeavesTheFieldSafe) {
  test::LoopRig r;
  r.core.requestDuty = 50.0;
  r.core.requestEnable = true;
  ControlLoop loop(*r.cycle, r.clock, r.stats, LoopConfig{});
  r.core.onStep = [&](const Inputs&) {
    if (r.core.steps == 10) loop.requestAbort();
  };
  loop.run();
  EXPECT_EQ(r.core.steps, 10);  // no ramp ticks
  EXPECT_TRUE(r.core.commands.empty());
  EXPECT_FALSE(r.enable.level);
  EXPECT_DOUBLE_EQ(r.pwm.duty, 0.0);
}

}  // namespace
}  // namespace xr::rt
