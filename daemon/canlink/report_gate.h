#pragma once
// ReportGate: the rate limit of the CAN side's reports (bad input
// is "counted and ignored, with a rate-limited event"). Fed the running
// total of something counted (bad frames, error frames), it lets the first
// increase of an incident through at once, then reports at growing
// intervals (kPeriodS, doubling up to kMaxPeriodS), each report carrying
// how many came since the one before: nothing is lost from the count, only
// from the number of lines. A BMS that sends a bad frame every second for
// hours gives 8 lines in its first hour and one an hour after (a journal
// of 1,200 lines in 10 h said nothing the first line had not). kQuietS
// without a new one ends the incident: the next one is reported at once.
#include <algorithm>
#include <cstdint>

#include "core/time.h"

namespace xr::canlink {

class ReportGate {
 public:
  static constexpr double kPeriodS = 30.0;
  static constexpr double kMaxPeriodS = 3600.0;
  static constexpr double kQuietS = 600.0;

  // Something of another kind came (a new reason for bad frames): the next
  // due() reports at once and the intervals start again from kPeriodS. The
  // caller restarts once per kind and incident, so the lines stay bounded.
  void restart() {
    periodS_ = kPeriodS;
    last_ = -1;
  }

  // How many to report now (0: nothing new, or too soon after the last).
  std::uint64_t due(std::uint64_t total, TimeNs now) {
    if (total != seen_) {
      // The first new one after kQuietS starts another incident: told at once.
      if (lastNew_ >= 0 && now - lastNew_ >= fromSec(kQuietS)) {
        periodS_ = kPeriodS;
        last_ = -1;
      }
      seen_ = total;
      lastNew_ = now;
    }
    if (total == reported_ || (last_ >= 0 && now - last_ < fromSec(periodS_))) return 0;
    if (last_ >= 0) periodS_ = std::min(periodS_ * 2.0, kMaxPeriodS);
    const std::uint64_t n = total - reported_;
    reported_ = total;
    last_ = now;
    return n;
  }

 private:
  std::uint64_t reported_ = 0, seen_ = 0;
  TimeNs last_ = -1, lastNew_ = -1;
  double periodS_ = kPeriodS;
};

}  // namespace xr::canlink
