#pragma once
// ReportGate: the rate limit of the CAN side's reports (bad input
// is "counted and ignored, with a rate-limited event"). Fed the running
// total of something counted (bad frames, error frames), it lets the first
// increase through at once and then at most one report per period, each
// carrying how many came since the one before: nothing is lost from the
// count, only from the number of lines.
#include <cstdint>

#include "core/time.h"

namespace xr::canlink {

class ReportGate {
 public:
  static constexpr double kPeriodS = 30.0;

  // How many to report now (0: nothing new, or too soon after the last).
  std::uint64_t due(std::uint64_t total, TimeNs now) {
    if (total == reported_ || (last_ >= 0 && now - last_ < fromSec(kPeriodS))) return 0;
    const std::uint64_t n = total - reported_;
    reported_ = total;
    last_ = now;
    return n;
  }

 private:
  std::uint64_t reported_ = 0;
  TimeNs last_ = -1;
};

}  // namespace xr::canlink
