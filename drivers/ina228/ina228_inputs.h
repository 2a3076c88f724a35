#pragma once
// Copies an INA228 driver state into the core's Inputs (RT-safe, inline).
// Call once per tick after Ina228Driver::poll(now).
#include "core/inputs.h"
#include "drivers/ina228/ina228_driver.h"

namespace xr {

inline void fillInaInputs(const Ina228Driver& d, Inputs& in) noexcept {
  const Ina228Sample& s = d.sample();
  in.inaPresent = d.present();
  in.inaFastModeActive = d.fastModeActive();
  in.IBV.value = s.busVolts;
  in.IBV.stamp = s.stamp;
  in.IBV.fresh = s.fresh && d.present();
  in.Bcur.value = s.currentA;  // before DynamicShuntGainFactor (the core applies it)
  in.Bcur.stamp = s.stamp;
  in.Bcur.fresh = in.IBV.fresh;
  in.inaBusOvervoltage = s.busOvervoltage;
  in.inaDiagStamp = s.diagStamp;
  in.inaDieTempC = s.dieTempC;
}

}  // namespace xr
