#pragma once
// FastSampleRates: the rates the fast over-voltage supervisors act on, from
// fresh INA228 samples (docs/protections.md "Group 1", "Load dump"): the
// dv/dt EMA (DvdtAlpha) of IBV and dBcur/dt with its three load-dump tiers.
// "dvdt sample window: 1-100 ms between INA samples ... slow mode rejected -
// dvdt holds last value."
#include "core/inputs.h"
#include "core/time.h"
#include "params/params.h"

namespace xr {

class FastSampleRates {
 public:
  // Every tick (from the detectors' step), whatever the mode.
  void update(const Inputs& in, const Params& p) noexcept;
  double dvdt() const noexcept { return dvdt_; }
  double dBcurDt() const noexcept { return dBcurDt_; }
  // A load-dump tier fired on this tick's sample, in INA228 fast mode.
  bool loadDump() const noexcept { return loadDump_; }

 private:
  void updateDvdt(const Reading& ibv, const Params& p) noexcept;
  void updateDBcurDt(const Reading& bcur, const Params& p) noexcept;

  double dvdt_ = 0.0;                      // V/s, EMA at DvdtAlpha
  double lastIbv_ = kNoValue;              // the previous accepted IBV sample
  TimeNs lastIbvStamp_ = 0;                // its stamp
  double dBcurDt_ = 0.0;                   // A/s, the last accepted sample pair
  double lastBcur_ = kNoValue;             // the previous Bcur sample
  TimeNs lastBcurStamp_ = 0;               // its stamp
  int over1_ = 0, over2_ = 0, over3_ = 0;  // consecutive samples over Thresh1 / Thresh / Thresh3
  bool loadDump_ = false;                  // a tier fired on this tick's sample (fast mode)
};

}  // namespace xr
