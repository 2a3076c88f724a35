#pragma once
// Test rig: drives a ProtectionSupervisor the way Regulator::step does
// (updateDetectors -> snapshot -> selectFieldMode -> runShutdownPath ->
// checkAlarms), with healthy sensor samples every tick unless a test freezes
// or overrides one. Control is simulated by a constant normal-mode duty.
#include <algorithm>
#include <vector>

#include "core/events.h"
#include "core/inputs.h"
#include "params/params.h"
#include "protection/mode_selection.h"
#include "protection/protection_supervisor.h"

namespace xr::test {

inline constexpr TimeNs kTick = fromMs(5);

struct Rig {
  Params p;
  ProtectionSupervisor sup;
  Inputs in;
  TimeNs t = fromSec(100.0);  // arbitrary monotonic origin
  // Sensor values (applied every tick).
  double ibv = 13.5, batteryV = 13.5, bcur = 10.0, altAmps = 20.0, rpm = 1500.0, tempF = 100.0;
  bool inaAlert = false;
  bool freezeTemp = false, freezeCh1 = false, freezeIna = false, freezeHeartbeat = false;
  // Operator state.
  bool manual = false, limp = false, OnOffOrder = true, ignition = true, bms = true, autoZero = false;
  bool effAnomaly = false;
  double normalDuty = 50.0;
  double rpmMinDuty = 5.0;
  double lastDuty = 50.0;

  ModeDecision d;
  ShutdownCommand sc;
  bool buzzer = false;
  EventBatch ev;
  std::vector<Event> log;

  explicit Rig(const Params& params = Params{}) : p(params), sup(params) {
    in.inaPresent = true;
    in.inaFastModeActive = true;
  }

  void setParams(const Params& np) {
    p = np;
    sup.setParams(np);
  }

  void fill() {
    in.now = t;
    auto put = [&](Reading& r, double v, bool frozen) {
      if (frozen) {
        r.fresh = false;
        return;
      }
      r.value = v;
      r.stamp = t;
      r.fresh = true;
    };
    put(in.IBV, ibv, freezeIna);
    put(in.Bcur, bcur, freezeIna);
    put(in.BatteryV, batteryV, false);
    put(in.altCurrentRaw, altAmps, freezeCh1);
    put(in.rpm, rpm, false);
    put(in.AlternatorTemperatureF, tempF, freezeTemp);
    if (!freezeHeartbeat) in.tempTaskHeartbeat = t;
    in.inaBusOvervoltage = inaAlert;
    in.ignitionOn = ignition;
    in.bmsChargeEnabled = bms;
  }

  TickSnapshot snapshot() const {
    TickSnapshot s;
    s.now = t;
    s.prot = sup.flags();
    s.limpHome = limp;
    s.manualMode = manual;
    s.ignitionOn = ignition;
    s.OnOff = OnOffOrder && p.OnOff;
    s.bmsChargeEnabled = bms;
    s.autoZeroActive = autoZero;
    return s;
  }

  void tick(TimeNs dt = kTick) {
    t += dt;
    fill();
    ev.clear();
    sup.updateDetectors(in, freezeCh1 ? in.altCurrentRaw.value : altAmps, ev);
    d = selectFieldMode(snapshot());
    sc = sup.runShutdownPath(d, lastDuty, rpmMinDuty, ev);
    lastDuty = sc.active ? sc.dutyPct : (manual ? normalDuty : normalDuty);
    buzzer = sup.checkAlarms(effAnomaly, ev);
    for (std::size_t i = 0; i < ev.count; ++i) log.push_back(ev.items[i]);
  }

  void run(TimeNs span, TimeNs dt = kTick) {
    const TimeNs end = t + span;
    while (t < end) tick(dt);
  }

  // Run until pred() or the time limit; returns elapsed time or -1.
  template <typename Pred>
  TimeNs runUntil(Pred pred, TimeNs limit, TimeNs dt = kTick) {
    const TimeNs start = t;
    while (t - start < limit) {
      tick(dt);
      if (pred()) return t - start;
    }
    return -1;
  }

  // Boot into steady normal operation (sensors read, INA fast mode settled).
  void warmUp() {
    run(fromSec(2.0));
    log.clear();
  }

  std::size_t count(EventCode c, Reason r) const {
    return static_cast<std::size_t>(
        std::count_if(log.begin(), log.end(), [&](const Event& e) { return e.code == c && e.reason == r; }));
  }
  std::size_t count(EventCode c) const {
    return static_cast<std::size_t>(
        std::count_if(log.begin(), log.end(), [&](const Event& e) { return e.code == c; }));
  }
};

}  // namespace xr::test
