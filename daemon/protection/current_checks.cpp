// CurrentChecks::update().
#include "protection/current_checks.h"

#include <algorithm>

#include "core/finite.h"
#include "params/constants.h"
#include "params/derived.h"

namespace xr {

void CurrentChecks::update(const CurrentChecksInput& in, const Params& p, const ProtectionLog& log) noexcept {
  const TimeNs now = log.now();
  if (in.inaFastMode && !inaFast_) inaFastSince_ = now;
  inaFast_ = in.inaFastMode;

  const double trip = hardOCTripAmps(p);
  hardOc_ = overT_.update(finite(in.MeasuredAmps) && in.MeasuredAmps > trip, now, fromMs(p.HardOCDebounceMs));
  evHardOc_.update(hardOc_, Reason::REASON_HARD_OVERCURRENT, in.MeasuredAmps, trip, log,
                   EventLevel::Critical);

  const TimeNs win = fromMs(p.CurrentStaleMs);
  auto staleOf = [&](TimeNs stamp, TimeNs window) { return now - (stamp != 0 ? stamp : in.boot) > window; };
  const bool ch1Stale = staleOf(in.ch1Stamp, win);
  const bool settledFast =
      inaFast_ && inaFastSince_ >= 0 && now - inaFastSince_ >= fromMs(k::INA_SLOW_INTERVAL_MS);
  const TimeNs inaWin = settledFast ? win : win + 2 * fromMs(k::INA_SLOW_INTERVAL_MS);
  const bool inaStale = !p.INADisconnected && staleOf(in.inaStamp, inaWin);
  stale_ = ch1Stale || inaStale;
  evStale_.update(stale_, Reason::REASON_CURRENT_STALE, ch1Stale ? 1.0 : 0.0, inaStale ? 1.0 : 0.0, log,
                  EventLevel::Critical);
}

}  // namespace xr
