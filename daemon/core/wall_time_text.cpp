#include "core/wall_time_text.h"

#include <ctime>

namespace xr {

std::string wallTimeText(std::int64_t unixMs, const char* format, TimeZone zone) {
  std::int64_t secs = unixMs / 1000;
  if (unixMs % 1000 < 0) --secs;  // floor, so -1 ms is the second before the epoch
  const std::time_t t = static_cast<std::time_t>(secs);
  std::tm tm{};
  if (zone == TimeZone::Utc) {
    gmtime_r(&t, &tm);
  } else {
    localtime_r(&t, &tm);
  }
  char buf[64];
  const std::size_t n = std::strftime(buf, sizeof buf, format, &tm);
  return std::string(buf, n);
}

}  // namespace xr
