#pragma once
// Drives ControlLaw directly in AUTO against the Plant, one CH1 sample per
// tick, the way Regulator::step does (without protections or battery).
#include "control/control_law.h"
#include "plant.h"

namespace xr::test {

struct LawRig {
  Params p;
  ControlLaw law;
  Plant plant;
  TimeNs now = fromSec(100.0);
  EventBatch ev;
  double rpm = 2000.0;
  double tempF = 100.0;
  TimeNs tempStamp = 0;
  double soc = kNoValue;
  bool manual = false;
  FastOvVerdict ov;  // what the fast-OV supervisors ask this tick (none by default)
  double duty = 0.0;
  bool bcurKnown = true;       // false: no battery current sensor
  bool sensorFailure = false;  // the bus voltage implausible or disagreeing critically

  explicit LawRig(const Params& params = Params{}) : p(params), law(params) {}

  ControlSensors sensors(bool fresh = true) const {
    ControlSensors s;
    s.now = now;
    s.ch1Fresh = fresh;
    s.MeasuredAmps = plant.Ialt;
    s.IBV = plant.V();
    s.ibvFresh = true;
    s.Bcur = bcurKnown ? plant.Ibat() : kNoValue;
    s.rpm = rpm;
    s.TempToUse = tempF;
    s.tempStamp = tempStamp;
    s.SOC_percent = soc;
    s.sensorFailureBypass = sensorFailure;
    return s;
  }

  void start() {
    tempStamp = now;
    law.updateFilters(sensors(), p);
    law.enterSysAuto(sensors(), p);
    law.onFieldTurnOn(now);
  }

  // One control tick of dt seconds: the sensors are read, the law runs, the
  // plant advances.
  double tick(double dt = 0.0025, bool fresh = true) {
    now += fromSec(dt);
    if (now - tempStamp >= fromSec(1.0)) tempStamp = now;  // 1 Hz temperature samples
    ev.clear();
    const ControlSensors s = sensors(fresh);
    law.updateFilters(s, p);
    law.updateChargingStage(s, p, manual, ev);
    if (manual) {
      duty = law.runManual(s, p, p.ManualDutyTarget);
    } else {
      law.computeUTarget(s, p);
      duty = law.finishAuto(s, p, ov, ev);
    }
    plant.advance(duty, true, dt);
    return duty;
  }

  void run(double seconds, double dt = 0.0025) {
    const long n = std::lround(seconds / dt);
    for (long i = 0; i < n; ++i) tick(dt);
  }
};

}  // namespace xr::test
