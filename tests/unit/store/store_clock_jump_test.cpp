// The chart history against a wall clock that jumps (docs/security.md "The
// clock"): a Pi without a real-time clock starts at its last saved
// time and NTP or a GPS then moves it by hours or days, either way. The
// store is handed the wall time of each sample (here a fake clock), so
// every jump is a test input.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>
#include <vector>

#include "store/schema.h"
#include "store/sqlite_db.h"
#include "store/store.h"
#include "store_test_util.h"

namespace xr {
namespace {

using test::kT0;
using test::TempDir;

constexpr std::int64_t kHourMs = 3600LL * 1000;

// Rows of the 1 s table whose bucket lies in [fromMs, toMs), read through a
// second connection: what a power cut now would leave on the card.
std::int64_t rowsOnDisk(const std::string& file, std::int64_t fromMs, std::int64_t toMs) {
  sql::Db db;
  EXPECT_EQ(db.open(file), 0);
  sql::Stmt st(db, "SELECT count(*) FROM history_1s_ring WHERE t_s >= ?1 AND t_s < ?2");
  st.bind(1, fromMs / 1000 - 60).bind(2, toMs / 1000);
  return st.step() == SQLITE_ROW ? st.colInt(0) : -1;
}

class ClockJump : public ::testing::TestWithParam<std::int64_t> {};

// 5 minutes of samples, the jump, 5 more minutes: the samples after the
// jump reach the card at the usual interval (before: a jump back of 3 h
// wrote nothing for 3 h), and both stretches read back, also after a
// restart.
TEST_P(ClockJump, HistoryIsStillWrittenAndKeptAcrossTheJump) {
  const std::int64_t jump = GetParam();
  TempDir d;
  StoreOptions opt;
  opt.historyFlushS = 120;
  const std::string file = d.file("h.db");
  const std::int64_t t0 = (kT0 / kHourMs) * kHourMs;
  const std::int64_t t1 = t0 + 300'000 + jump;  // where the clock lands
  {
    Store s(opt);
    ASSERT_TRUE(s.open(file, t0).ok);
    std::vector<double> v(opt.historySeries.size(), NAN);
    for (int sec = 0; sec < 300; ++sec) {
      v[0] = 13.0 + sec / 1000.0;
      ASSERT_TRUE(s.appendHistory(t0 + sec * 1000LL, v).ok);
    }
    for (int sec = 0; sec < 300; ++sec) {
      v[0] = 14.0 + sec / 1000.0;
      ASSERT_TRUE(s.appendHistory(t1 + sec * 1000LL, v).ok);
    }
    EXPECT_GT(rowsOnDisk(file, t1, t1 + 300'000), 0) << "nothing after the jump reached the card";
    EXPECT_EQ(s.queryHistory("ibv_v", t1, t1 + 299'000, 0).size(), 300u);
    s.close();
  }
  Store s2(opt);
  ASSERT_TRUE(s2.open(file, t1 + 300'000).ok);
  const auto after = s2.queryHistory("ibv_v", t1, t1 + 299'000, 0);
  ASSERT_EQ(after.size(), 300u);
  EXPECT_NEAR(after.front().value, 14.0, 1e-4);
  const auto before = s2.queryHistory("ibv_v", t0, t0 + 299'000, 0);
  if (jump > 48 * kHourMs) {
    // A jump beyond the 1 s retention: those rows are due for deletion, and
    // the minute means (kept a year) still hold the stretch.
    EXPECT_TRUE(before.empty() || before.size() == 300u);
    EXPECT_GE(s2.queryHistory("ibv_v", t0, t0 + 299'000, 60'000).size(), 4u);
  } else {
    ASSERT_EQ(before.size(), 300u);
    EXPECT_NEAR(before.front().value, 13.0, 1e-4);
  }
}

INSTANTIATE_TEST_SUITE_P(ForwardAndBack, ClockJump,
                         ::testing::Values(3 * kHourMs, -3 * kHourMs, 720 * kHourMs, -720 * kHourMs),
                         [](const ::testing::TestParamInfo<std::int64_t>& i) {
                           const std::int64_t h = i.param / kHourMs;
                           return std::string(h > 0 ? "Forward" : "Back") + std::to_string(h > 0 ? h : -h) +
                                  "h";
                         });

}  // namespace
}  // namespace xr
