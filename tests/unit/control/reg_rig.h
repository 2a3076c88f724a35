#pragma once
// Drives the whole Regulator (control + protections + battery) against the
// Plant with healthy sensors, one tick per 2.5 ms, every channel fresh.
#include "control/regulator.h"
#include "plant.h"

namespace xr::test {

struct RegRig {
  Params p;
  Regulator reg;
  Plant plant;
  TimeNs now = fromSec(1.0);
  double rpm = 2000.0;
  double tempF = 100.0;
  TimeNs tempStamp = 0;
  bool ch1Fresh = true;
  BmsLimits bms;  // a BMS's limits as posted (stamp 0 = none)
  const Outputs* out = nullptr;

  explicit RegRig(const Params& params = Params{}) : p(params), reg(params) {}

  Inputs inputs() const {
    Inputs in;
    in.now = now;
    in.inaPresent = true;
    const double v = plant.V();
    in.IBV = {v, now, true};
    in.Bcur = {plant.Ibat(), now, true};
    in.inaDiagStamp = now;
    in.BatteryV = {v, now, true};
    in.altCurrentRaw = {plant.Ialt, now, ch1Fresh};
    in.rpm = {rpm, now, true};
    in.thermistorF = {tempF, now, true};
    in.AlternatorTemperatureF = {tempF, tempStamp, tempStamp == now};
    in.tempTaskHeartbeat = now;
    in.ignitionOn = true;
    in.bmsChargeEnabled = true;
    in.bms = bms;
    return in;
  }

  const Outputs& tick(double dt = 0.0025) {
    now += fromSec(dt);
    if (now - tempStamp >= fromSec(1.0)) tempStamp = now;
    out = &reg.step(inputs());
    plant.advance(out->dutyPct, out->fieldEnable, dt);
    return *out;
  }

  // Runs `seconds`; returns how many events with `code` were seen.
  int run(double seconds, EventCode code = EventCode::Message) {
    int seen = 0;
    const long n = std::lround(seconds / 0.0025);
    for (long i = 0; i < n; ++i) {
      const Outputs& o = tick();
      for (std::size_t k = 0; k < o.events.count; ++k) seen += o.events.items[k].code == code;
    }
    return seen;
  }
};

}  // namespace xr::test
