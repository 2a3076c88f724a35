#pragma once
// The runtime's adapter of the slow sensor readers to the core: copies their
// published samples into the core's Inputs (RT-safe, inline). `fresh` is true when the sample's stamp moved
// since the previous tick; the caller keeps the previous stamps in SlowInputsState.
#include "core/inputs.h"
#include "drivers/onewire/ds18b20_reader.h"
#include "drivers/vedirect/vedirect_reader.h"

namespace xr {

struct SlowInputsState {
  TimeNs tempStamp = 0;
  TimeNs victronStamp = 0;
};

// DS18B20: value, stamp (T5 stale check) and the task heartbeat (T4).
inline void fillTempInputs(const Ds18b20Sample& s, SlowInputsState& st, Inputs& in) noexcept {
  in.tempTaskHeartbeat = s.heartbeat;
  in.AlternatorTemperatureF.fresh = s.stamp != 0 && s.stamp != st.tempStamp;
  if (s.stamp != 0) {
    in.AlternatorTemperatureF.value = s.tempF;
    in.AlternatorTemperatureF.stamp = s.stamp;
  }
  st.tempStamp = s.stamp;
}

// VE.Direct: current (BatteryCurrentSource = 3), voltage and panel power
// (solar energy). A label never seen keeps its Reading empty.
inline void fillVictronInputs(const VeDirectSample& s, SlowInputsState& st, Inputs& in) noexcept {
  const bool fresh = s.stamp != 0 && s.stamp != st.victronStamp;
  auto put = [&](Reading& r, bool has, double v) {
    r.fresh = fresh && has;
    if (has && s.stamp != 0) {
      r.value = v;
      r.stamp = s.stamp;
    }
  };
  put(in.VictronCurrent, s.hasCurrent, s.currentA);
  put(in.VictronVoltage, s.hasVoltage, s.voltageV);
  put(in.solarPowerW, s.hasPpv, s.ppvW);
  st.victronStamp = s.stamp;
}

}  // namespace xr
