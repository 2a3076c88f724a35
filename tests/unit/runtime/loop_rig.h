#pragma once
// The control loop's test rig: a ControlCycle over fakes, driven by a fake
// clock (shared by the control-loop test files).
#include <memory>

#include "fakes.h"
#include "runtime/control_cycle.h"
#include "runtime/loop_stats.h"

namespace xr::rt::test {

struct LoopRig {
  LoopRig() : handoffs(Params{}), pwm(log), enable(log, 'E') {
    dev.sensors = &sensors;
    dev.pwm = &pwm;
    dev.fieldEnable = &enable;
    dev.watchdog = &watchdog;
    cycle = std::make_unique<ControlCycle>(core, dev, handoffs, stats, clock, CycleConfig{});
  }
  test::ScriptedCore core;
  Handoffs handoffs;
  LoopStats stats;
  FakeClock clock;
  test::OutputLog log;
  test::FakeSensors sensors;
  test::FakePwm pwm;
  test::FakeDigitalOut enable;
  test::FakeWatchdog watchdog;
  CycleDevices dev;
  std::unique_ptr<ControlCycle> cycle;
};

// A wall clock that jumps forward at a chosen read: the thread woke late
// (another process or the hypervisor had the CPU), not because of its own
// tick.
class JumpingWall final : public Clock {
 public:
  TimeNs now() const noexcept override {
    if (jumpInReads == 0) t += jump;
    if (jumpInReads >= 0) --jumpInReads;
    return t;
  }
  void sleepUntil(TimeNs until) noexcept override {
    if (until > t) t = until;
  }
  mutable TimeNs t = 5'000'000'000;
  mutable int jumpInReads = -1;
  TimeNs jump = 0;
};

}  // namespace xr::rt::test
