#pragma once
// Wall-clock milliseconds as text, for names, logs and the owner's calendar
// day. One home for the gmtime_r/localtime_r + strftime dance, which four
// places had written again. The control core never reads this: its time is
// monotonic (core/time.h).
#include <cstdint>
#include <string>

namespace xr {

enum class TimeZone { Utc, Local };

// `format` is a strftime format; the result is cut at 63 characters.
// Negative times floor to the earlier second (1969-12-31 23:59:59 for -1 ms).
std::string wallTimeText(std::int64_t unixMs, const char* format, TimeZone zone);

}  // namespace xr
