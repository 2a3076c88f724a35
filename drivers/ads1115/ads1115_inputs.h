#pragma once
// Copies ADS1115 samples (already scaled by the analog front end) into the
// core's Inputs (RT-safe, inline). Call once per tick with poll(now)'s result.
#include "core/inputs.h"
#include "drivers/ads1115/ads1115_driver.h"

namespace xr {

inline void fillAdsInputs(const Ads1115Samples& s, Inputs& in) noexcept {
  Reading* dst[4] = {&in.BatteryV, &in.altCurrentRaw, &in.rpm, &in.thermistorF};
  for (std::size_t i = 0; i < 4; ++i) {
    dst[i]->value = s.ch[i].value;
    dst[i]->stamp = s.ch[i].stamp;
    dst[i]->fresh = s.ch[i].fresh && s.present;
  }
}

}  // namespace xr
