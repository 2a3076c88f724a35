#include "app/patch_log_limiter.h"

#include <fmt/format.h>

namespace xr::app {

std::string PatchLogLimiter::onPatch(Clock::time_point now, std::size_t values) {
  if (!quiet(now)) {
    ++heldPatches_;
    heldValues_ += values;
    return "";
  }
  // Anything held back since the last line goes into this one.
  std::string line =
      fmt::format("parameters changed through the API: {} value{}", values, values == 1 ? "" : "s");
  if (heldPatches_ > 0)
    line += fmt::format(" (and {} earlier change{} of {} values not logged one by one: suppressed {})",
                        heldPatches_, heldPatches_ == 1 ? "" : "s", heldValues_, heldPatches_);
  line += "; each change is in the event list";
  logged_ = true;
  lastLine_ = now;
  heldPatches_ = heldValues_ = 0;
  return line;
}

std::string PatchLogLimiter::flush(Clock::time_point now) {
  if (heldPatches_ == 0 || !quiet(now)) return "";
  return summary(now);
}

std::string PatchLogLimiter::summary(Clock::time_point now) {
  const auto secs = std::chrono::duration_cast<std::chrono::seconds>(now - lastLine_).count();
  std::string line = fmt::format(
      "parameters changed through the API: suppressed {} more change{} ({} values) in the {} s since the "
      "last "
      "such line; each change is in the event list",
      heldPatches_, heldPatches_ == 1 ? "" : "s", heldValues_, secs);
  lastLine_ = now;
  heldPatches_ = heldValues_ = 0;
  return line;
}

}  // namespace xr::app
