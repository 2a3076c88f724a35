// The wall-clock text the store names its copies with and the history keys
// its days by (core/wall_time_text.h).
#include "core/wall_time_text.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace xr {
namespace {

TEST(WallTimeText, UtcAtTheEpochAndAfter) {
  EXPECT_EQ(wallTimeText(0, "%Y-%m-%dT%H:%M:%S", TimeZone::Utc), "1970-01-01T00:00:00");
  EXPECT_EQ(wallTimeText(1700000000123LL, "%Y%m%dT%H%M%SZ", TimeZone::Utc), "20231114T221320Z");
}

TEST(WallTimeText, ATimeBeforeTheEpochIsTheSecondItFallsIn) {
  // -1 ms is 23:59:59.999 on the last day of 1969, not the epoch itself.
  EXPECT_EQ(wallTimeText(-1, "%Y-%m-%d %H:%M:%S", TimeZone::Utc), "1969-12-31 23:59:59");
}

TEST(WallTimeText, LocalFollowsTheBoardsTimeZone) {
  const char* old = std::getenv("TZ");
  const std::string saved = old ? old : "";
  setenv("TZ", "XRT-13", 1);  // a POSIX zone 13 h east of UTC: no tzdata needed
  tzset();
  const std::string day = wallTimeText(1700000000123LL, "%Y-%m-%d %H", TimeZone::Local);
  if (old) {
    setenv("TZ", saved.c_str(), 1);
  } else {
    unsetenv("TZ");
  }
  tzset();
  EXPECT_EQ(day, "2023-11-15 11");
}

TEST(WallTimeText, AFormatTooLongForTheBufferGivesEmptyTextNotGarbage) {
  const std::string longFormat(80, 'x');
  EXPECT_EQ(wallTimeText(0, longFormat.c_str(), TimeZone::Utc), "");
}

}  // namespace
}  // namespace xr
