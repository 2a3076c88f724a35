#pragma once
// Copies ADS1115 samples (already scaled by the analog front end) into the
// core's Inputs (RT-safe, inline). Call once per tick with poll(now)'s result.
#include "core/inputs.h"
#include "drivers/ads1115/ads1115_driver.h"

namespace xr {

inline void fillAdsInputs(const Ads1115Samples& s, Inputs& in) noexcept {
  const bool present = s.present;
  auto put = [present](Reading& r, const AdsChannelSample& c) {
    r.value = c.value;
    r.stamp = c.stamp;
    r.fresh = c.fresh && present;
  };
  put(in.BatteryV, s.ch[0]);
  put(in.altCurrentRaw, s.ch[1]);
  put(in.rpm, s.ch[2]);
  put(in.thermistorF, s.ch[3]);
}

}  // namespace xr
