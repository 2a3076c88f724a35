#pragma once
// Drives a BatteryMonitor the way Regulator::step does, with injected time.
#include <functional>

#include "battery/battery_monitor.h"
#include "params/params.h"

namespace xr::test {

struct BatteryRig {
  Params p;
  BatteryMonitor mon;
  TimeNs now = fromSec(1000.0);  // monotonic clocks do not start at 0
  EventBatch ev;
  Inputs in;

  explicit BatteryRig(const Params& params) : p(params), mon(params) {}

  // Sets the INA228 sample (fresh, stamped now).
  void ina(double volts, double amps) {
    in.IBV = Reading{volts, now, true};
    in.Bcur = Reading{amps, now, true};
  }
  // One tick of dt seconds: the sample set before it is held over the tick.
  void tick(double dt_s, double altRaw = 0.0) {
    now += fromSec(dt_s);
    in.now = now;
    if (in.IBV.stamp != 0) in.IBV.stamp = now;
    if (in.Bcur.stamp != 0) in.Bcur.stamp = now;
    in.altCurrentRaw = Reading{altRaw, now, true};
    ev.clear();
    mon.checkAutoZeroTriggers(in, ev);
    mon.processAutoZero(in, ev);
    mon.updateBatterySoc(in, mon.correctedAltAmps(altRaw), ev);
  }
  // Runs for `seconds` at `dt` with the current sample.
  void run(double seconds, double dt, double altRaw = 0.0) {
    const long n = static_cast<long>(seconds / dt + 0.5);
    for (long i = 0; i < n; ++i) tick(dt, altRaw);
  }
  BatteryTelemetry telem() const {
    BatteryTelemetry t;
    mon.fillTelemetry(t);
    return t;
  }
  bool sawEvent(EventCode c) const {
    for (std::size_t i = 0; i < ev.count; ++i)
      if (ev.items[i].code == c) return true;
    return false;
  }
};

}  // namespace xr::test
