// FastSampleRates::update().
#include "protection/fast_samples.h"

#include "core/finite.h"
#include "params/constants.h"

namespace xr {

void FastSampleRates::update(const Inputs& in, const Params& p) noexcept {
  updateDvdt(in.IBV, p);
  bool fired = false;
  if (in.Bcur.fresh && in.Bcur.stamp != lastBcurStamp_ && finite(in.Bcur.value)) {
    updateDBcurDt(in.Bcur, p);
    fired = over1_ >= 1 || over2_ >= 2 || over3_ >= 3;
  }
  // The load dump acts only on fast-mode samples (a slow-mode pair is ~1 s apart).
  loadDump_ = fired && in.inaFastModeActive;
}

void FastSampleRates::updateDvdt(const Reading& ibv, const Params& p) noexcept {
  if (!ibv.fresh || ibv.stamp == lastIbvStamp_ || !finite(ibv.value)) return;
  if (lastIbvStamp_ != 0 && finite(lastIbv_)) {
    const double dt = toSec(ibv.stamp - lastIbvStamp_);
    if (dt >= k::DVDT_MIN_SAMPLE_S && dt <= k::DVDT_MAX_SAMPLE_S) {
      const double raw = (ibv.value - lastIbv_) / dt;
      dvdt_ += p.DvdtAlpha * (raw - dvdt_);
    }
  }
  lastIbv_ = ibv.value;
  lastIbvStamp_ = ibv.stamp;
}

// Three tiers: 1 sample over LoadDumpDtThresh1, 2 consecutive over
// LoadDumpDtThresh, 3 over LoadDumpDtThresh3; a pair outside the sample
// window restarts the counts.
void FastSampleRates::updateDBcurDt(const Reading& bcur, const Params& p) noexcept {
  bool accepted = false;
  if (lastBcurStamp_ != 0 && finite(lastBcur_)) {
    const double dt = toSec(bcur.stamp - lastBcurStamp_);
    if (dt >= k::DVDT_MIN_SAMPLE_S && dt <= k::DVDT_MAX_SAMPLE_S) {
      dBcurDt_ = (bcur.value - lastBcur_) / dt;
      accepted = true;
    }
  }
  if (accepted) {
    over1_ = dBcurDt_ > p.LoadDumpDtThresh1 ? over1_ + 1 : 0;
    over2_ = dBcurDt_ > p.LoadDumpDtThresh ? over2_ + 1 : 0;
    over3_ = dBcurDt_ > p.LoadDumpDtThresh3 ? over3_ + 1 : 0;
  } else {
    over1_ = over2_ = over3_ = 0;
  }
  lastBcur_ = bcur.value;
  lastBcurStamp_ = bcur.stamp;
}

}  // namespace xr
