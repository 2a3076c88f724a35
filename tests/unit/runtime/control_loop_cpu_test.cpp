// Whose overrun is it ("0 overruns attributable to the daemon")?
// The loop judges by the control thread's CPU time per tick, read through
// LoopConfig::cpuTime (CLOCK_THREAD_CPUTIME_ID on the daemon, a counter the
// test moves here): a tick that used a period of CPU is the daemon's; a tick
// preempted inside, or a late wake-up, is the machine's.
#include <gtest/gtest.h>

#include "loop_rig.h"
#include "runtime/control_loop.h"

namespace xr::rt {
namespace {

constexpr TimeNs kPeriod = fromUs(2500);

// A paced loop at speed 1 (wall deadline = virtual deadline) whose tick 10
// takes `wallStall` of wall time and `cpu` of CPU time; every other tick
// takes 20 µs of CPU and no wall time.
struct CpuRig {
  explicit CpuRig(TimeNs wallStall, TimeNs cpu) {
    cfg.duration = fromMs(100);  // 40 deadlines
    cfg.wall = &wall;
    virt0 = r.clock.t;
    wall0 = wall.t;
    cfg.wallDeadlineOf = [this](TimeNs t) { return wall0 + (t - virt0); };
    cfg.cpuTime = [this] { return cpuNow; };
    r.core.onStep = [this, wallStall, cpu](const Inputs&) {
      wall.t = std::max(wall.t, cfg.wallDeadlineOf(r.clock.t));
      if (r.core.steps == 10) {
        wall.t += wallStall;
        cpuNow += cpu;
      } else {
        cpuNow += fromUs(20);
      }
    };
  }
  LoopStatsSummary run() {
    ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
    loop.run();
    return r.stats.summary();
  }
  test::LoopRig r;
  test::FakeClock wall;
  LoopConfig cfg;
  TimeNs virt0 = 0, wall0 = 0, cpuNow = 0;
};

TEST(ControlLoopCpu, ATickThatUsesMoreThanAPeriodOfCpuIsTheDaemons) {
  CpuRig rig(kPeriod * 3 + fromUs(100), kPeriod * 3 + fromUs(100));  // 7.6 ms of work
  const auto s = rig.run();
  EXPECT_EQ(s.overruns, 2u);
  EXPECT_EQ(s.overrunsOwn, 2u);
  EXPECT_DOUBLE_EQ(s.tickCpuMaxUs, 7600.0);
}

TEST(ControlLoopCpu, APreemptedShortTickIsAnOverrunButNotTheDaemons) {
  // 7.6 ms of wall inside the tick (a hypervisor stall), 50 µs of CPU.
  CpuRig rig(kPeriod * 3 + fromUs(100), fromUs(50));
  const auto s = rig.run();
  EXPECT_EQ(s.overruns, 2u);
  EXPECT_EQ(s.overrunsOwn, 0u);
  EXPECT_DOUBLE_EQ(s.tickCpuMaxUs, 50.0);
}

TEST(ControlLoopCpu, OwnAtExactlyOnePeriodOfCpuNotJustBelow) {
  CpuRig at(kPeriod * 3 + fromUs(100), kPeriod);
  EXPECT_EQ(at.run().overrunsOwn, 2u);
  CpuRig below(kPeriod * 3 + fromUs(100), kPeriod - 1);
  const auto s = below.run();
  EXPECT_EQ(s.overruns, 2u);
  EXPECT_EQ(s.overrunsOwn, 0u);
}

TEST(ControlLoopCpu, NoMissedDeadlineNoOverrunWhateverTheCpu) {
  // A tick that used 2.4 ms of CPU and finished inside its period.
  CpuRig rig(fromUs(2400), fromUs(2400));
  const auto s = rig.run();
  EXPECT_EQ(s.overruns, 0u);
  EXPECT_EQ(s.overrunsOwn, 0u);
  EXPECT_DOUBLE_EQ(s.tickCpuMaxUs, 2400.0);
}

TEST(ControlLoopCpu, ALateWakeUpIsNotTheDaemons) {
  test::LoopRig r;
  test::JumpingWall wall;
  LoopConfig cfg;
  cfg.duration = fromMs(100);
  cfg.wall = &wall;
  const TimeNs virt0 = r.clock.t, wall0 = wall.t;
  cfg.wallDeadlineOf = [&](TimeNs t) { return wall0 + (t - virt0); };
  TimeNs cpu = 0;
  cfg.cpuTime = [&] { return cpu; };
  r.core.onStep = [&](const Inputs&) {
    wall.t = std::max(wall.t, cfg.wallDeadlineOf(r.clock.t));
    cpu += fromUs(20);
    if (r.core.steps == 10) {
      wall.jump = kPeriod * 4 + fromUs(100);  // the next wake-up is 7.6 ms late
      wall.jumpInReads = 1;
    }
  };
  ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
  loop.run();
  const auto s = r.stats.summary();
  EXPECT_EQ(s.overruns, 2u);
  EXPECT_EQ(s.overrunsOwn, 0u);
  EXPECT_DOUBLE_EQ(s.tickCpuMaxUs, 20.0);
}

TEST(ControlLoopCpu, UnpacedLoopJudgesByCpuToo) {
  // --speed max / a loop without a wall clock: the loop clock stalls 7.6 ms
  // inside tick 10 while the thread used 30 µs of CPU.
  test::LoopRig r;
  LoopConfig cfg;
  cfg.duration = fromMs(100);
  TimeNs cpu = 0;
  cfg.cpuTime = [&] { return cpu; };
  r.core.onStep = [&](const Inputs&) {
    cpu += fromUs(30);
    if (r.core.steps == 10) r.clock.t += kPeriod * 3 + fromUs(100);
  };
  ControlLoop loop(*r.cycle, r.clock, r.stats, cfg);
  loop.run();
  EXPECT_EQ(r.stats.summary().overruns, 2u);
  EXPECT_EQ(r.stats.summary().overrunsOwn, 0u);
}

}  // namespace
}  // namespace xr::rt
