#pragma once
// Test doubles for the runtime: a virtual clock, a scripted core, recording
// outputs and sensors.
#include <cstdint>
#include <functional>
#include <vector>

#include "drivers/hal/clock.h"
#include "runtime/control_core.h"
#include "runtime/cycle_devices.h"

namespace xr::rt::test {

class FakeClock final : public Clock {
 public:
  TimeNs now() const noexcept override { return t; }
  void sleepUntil(TimeNs until) noexcept override {
    ++sleeps;
    if (until > t) t = until;
  }
  TimeNs t = 1'000'000'000;
  int sleeps = 0;
};

// A core whose outputs the test scripts: duty/enable follow `request` until
// an Off command, after which it ramps the duty down by rampStep per tick and
// drops the enable at 0 (like MODE_DISABLED_RAMP).
class ScriptedCore final : public ControlCore {
 public:
  const Outputs& step(const Inputs& in) override {
    ++steps;
    lastInputs = in;
    out.events.clear();
    if (onStep) onStep(in);
    if (off) {
      out.dutyPct = std::max(0.0, out.dutyPct - rampStep);
      out.fieldEnable = out.dutyPct > 0.0;
    } else {
      out.dutyPct = requestDuty;
      out.fieldEnable = requestEnable;
    }
    out.buzzer = requestBuzzer;
    out.telemetry.duty_pct = out.dutyPct;
    out.telemetry.field_enable = out.fieldEnable;
    out.telemetry.ibv_v = in.IBV.value;
    for (int i = 0; i < eventsPerTick; ++i) {
      Event e;
      e.code = EventCode::Message;
      e.a = static_cast<double>(steps);
      out.events.push(e);
    }
    return out;
  }
  void setParams(const Params& p) override {
    params = p;
    ++paramSets;
  }
  bool command(const Command& c) override {
    commands.push_back(c);
    if (c.type == CommandType::Off) off = true;
    return !rejectCommands;
  }

  Outputs out;
  Inputs lastInputs;
  Params params;
  std::vector<Command> commands;
  double requestDuty = 0.0;
  bool requestEnable = false;
  bool requestBuzzer = false;
  bool off = false;
  bool rejectCommands = false;
  double rampStep = 10.0;
  int eventsPerTick = 0;
  int steps = 0;
  int paramSets = 0;
  std::function<void(const Inputs&)> onStep;
};

struct FakeSensors final : FastSensors {
  bool read(TimeNs now, Inputs& in) noexcept override {
    ++reads;
    counts_ = counting ? &counts : nullptr;
    in.inaPresent = true;
    in.IBV = Reading{ibv, now, true};
    in.altCurrentRaw = Reading{10.0, now, true};
    in.BatteryV.fresh = (reads % 4) == 0;
    if (in.BatteryV.fresh) in.BatteryV = Reading{ibv, now, true};
    return ok;
  }
  void apply(const Outputs& out) noexcept override {
    lastFast = out.inaFastMode;
    ++applies;
  }
  // Ready-edge pacing: each edge is one CH1 result (when counting).
  void onReadyEdge(TimeNs edge) noexcept override {
    edges.push_back(edge);
    ++counts.ads[1];
  }
  double ibv = 13.2;
  bool ok = true;
  bool counting = false;
  SampleCounts counts{};
  std::vector<TimeNs> edges;
  int reads = 0, applies = 0;
  bool lastFast = false;
};

// ALERT/RDY edges every `period` on the test's clock, up to each deadline.
struct FakeEdges final : ReadyEdgeSource {
  explicit FakeEdges(TimeNs& clockTime) : t(clockTime) {}
  int waitEdge(TimeNs deadline, TimeNs* stamp) noexcept override {
    ++waits;
    if (fail) return -1;
    if (next == 0) next = t + period;
    if (next >= deadline) return 0;
    t = next;
    *stamp = next;
    next += period;
    return 1;
  }
  TimeNs& t;
  TimeNs period = 1'162'791;  // 860 SPS
  TimeNs next = 0;
  bool fail = false;
  int waits = 0;
};

// Records every write in order, to check sequencing (enable LOW first...).
struct OutputLog {
  struct Entry {
    char what;  // 'D' duty, 'E' enable, 'B' buzzer
    double value;
  };
  std::vector<Entry> entries;
};

struct FakePwm final : PwmOutput {
  explicit FakePwm(OutputLog& l) : log(l) {}
  bool setDutyPercent(double pct) noexcept override {
    if (fail) return false;
    duty = pct;
    log.entries.push_back({'D', pct});
    return true;
  }
  bool setEnabled(bool) noexcept override { return !fail; }
  OutputLog& log;
  double duty = -1;
  bool fail = false;
};

struct FakeDigitalOut final : DigitalOutput {
  FakeDigitalOut(OutputLog& l, char w) : log(l), what(w) {}
  bool set(bool high) noexcept override {
    if (fail) return false;
    level = high;
    log.entries.push_back({what, high ? 1.0 : 0.0});
    return true;
  }
  OutputLog& log;
  char what;
  bool level = false;
  bool fail = false;
};

struct FakeDigitalIn final : DigitalInput {
  int get() noexcept override { return value; }
  int value = 1;
};

struct FakeWatchdog final : Watchdog {
  bool keepAlive() noexcept override {
    ++feeds;
    return true;
  }
  void closeClean() noexcept override { closed = true; }
  int feeds = 0;
  bool closed = false;
};

}  // namespace xr::rt::test
