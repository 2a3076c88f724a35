#pragma once
// The journal's rate limit for settings changes through the API (docs/security.md):
// without it 2,000 PATCHes wrote 2,000 lines. The first change after a quiet
// interval is logged at once; the ones that follow within the interval are
// counted, and one summary line says how many were held back once the
// interval has passed (at the next change, or from the once-a-second
// housekeeping, so a burst followed by silence is still reported). Each
// change is in the event list anyway (who changed what).
// Not thread-safe: WebApi holds its log mutex around it.
#include <chrono>
#include <cstddef>
#include <string>

namespace xr::app {

class PatchLogLimiter {
 public:
  using Clock = std::chrono::steady_clock;
  explicit PatchLogLimiter(Clock::duration interval = std::chrono::minutes(1)) : interval_(interval) {}

  // A change of `values` values at `now`: the line to log, or "" when it is
  // held back (counted for the summary).
  std::string onPatch(Clock::time_point now, std::size_t values);
  // The summary of the changes held back, once the interval since the last
  // line has passed; "" otherwise.
  std::string flush(Clock::time_point now);

 private:
  bool quiet(Clock::time_point now) const { return !logged_ || now - lastLine_ >= interval_; }
  std::string summary(Clock::time_point now);

  Clock::duration interval_;
  bool logged_ = false;
  Clock::time_point lastLine_{};
  std::size_t heldPatches_ = 0, heldValues_ = 0;
};

}  // namespace xr::app
