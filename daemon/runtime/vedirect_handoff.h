#pragma once
// A VE.Direct sample as the control cycle's hand-off (Handoffs::victron), the
// way the DS18B20's is (ds18b20_handoff.h): the reader's own thread posts it
// with each new block, and the control thread reads that one hand-off
// (ControlCycle::mergeVictron); nothing relays it on the control thread.
#include "drivers/vedirect/vedirect_reader.h"
#include "runtime/handoffs.h"

namespace xr {

// The values of a block: a voltage or solar power the device has not sent is
// NaN (no value), never 0.
inline rt::VictronHandoff victronHandoff(const VeDirectSample& s) noexcept {
  rt::VictronHandoff vh;
  vh.currentA = s.currentA;
  vh.voltageV = s.hasVoltage ? s.voltageV : kNoValue;
  vh.solarW = s.hasPpv ? s.ppvW : kNoValue;
  vh.stamp = s.stamp;
  return vh;
}

// The reader's sink: posts only once the device has sent a current (I), the
// reading BatteryCurrentSource = 3 counts; a block without one keeps the
// hand-off as it was.
inline void postVeDirect(rt::Handoffs& h, const VeDirectSample& s) noexcept {
  if (s.hasCurrent) h.victron.store(victronHandoff(s));
}

}  // namespace xr
