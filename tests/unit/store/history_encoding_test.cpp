// The chart history's int16 rows (store/history_encoding.h): the round trip
// at its limits, the empty slot, and the float32 rows of a database written
// before, read and merged as they are.
#include "store/history_encoding.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "store/schema.h"
#include "store/store.h"
#include "store_test_util.h"

namespace xr {
namespace {

using test::kT0;
using test::TempDir;

std::vector<float> roundTrip(const std::vector<float>& in, double step) {
  std::vector<float> out(store::kHistorySlots, -1.0f);
  const auto blob = store::encodeHistoryRow(in, step);
  EXPECT_EQ(blob.size(), store::kInt16RowBytes);
  EXPECT_TRUE(store::decodeHistoryRow(blob, step, out));
  return out;
}

TEST(HistoryEncoding, RoundTripWithinHalfAStep) {
  std::vector<float> in(store::kHistorySlots);
  for (int i = 0; i < store::kHistorySlots; ++i) in[i] = 11.0f + 0.0137f * static_cast<float>(i);
  const auto out = roundTrip(in, 0.01);
  for (int i = 0; i < store::kHistorySlots; ++i) EXPECT_NEAR(out[i], in[i], 0.005 + 1e-5) << i;
}

TEST(HistoryEncoding, LimitsAreKeptAndBeyondThemClamped) {
  std::vector<float> in(store::kHistorySlots, NAN);
  in[0] = 327.67f;   // the largest count, 32767 steps
  in[1] = -327.67f;  // the smallest a value may be (-32768 means empty)
  in[2] = 400.0f;    // beyond: the limit, not a wrapped number
  in[3] = -400.0f;
  in[4] = INFINITY;
  in[5] = -INFINITY;
  in[6] = 0.0f;
  in[7] = -0.004f;  // rounds to 0
  const auto out = roundTrip(in, 0.01);
  EXPECT_NEAR(out[0], 327.67, 1e-3);
  EXPECT_NEAR(out[1], -327.67, 1e-3);
  EXPECT_NEAR(out[2], 327.67, 1e-3);
  EXPECT_NEAR(out[3], -327.67, 1e-3);
  EXPECT_NEAR(out[4], 327.67, 1e-3);
  EXPECT_NEAR(out[5], -327.67, 1e-3);
  EXPECT_EQ(out[6], 0.0f);
  EXPECT_EQ(out[7], 0.0f);
  for (int i = 8; i < store::kHistorySlots; ++i) EXPECT_TRUE(std::isnan(out[i])) << i;
}

TEST(HistoryEncoding, NanIsAnEmptySlot) {
  const std::vector<float> in(store::kHistorySlots, NAN);
  const auto blob = store::encodeHistoryRow(in, 0.1);
  for (std::size_t i = 0; i < blob.size(); i += 2) {
    EXPECT_EQ(blob[i], 0x00);
    EXPECT_EQ(blob[i + 1], 0x80);  // INT16_MIN, little-endian
  }
  for (float v : roundTrip(in, 0.1)) EXPECT_TRUE(std::isnan(v));
}

TEST(HistoryEncoding, OtherLengthsAreRefused) {
  std::vector<float> out(store::kHistorySlots, 7.0f);
  const std::vector<std::uint8_t> odd(100, 0);
  EXPECT_FALSE(store::decodeHistoryRow(odd, 0.01, out));
  EXPECT_EQ(out[0], 7.0f);  // untouched
}

TEST(HistoryEncoding, StepsPerSeries) {
  EXPECT_DOUBLE_EQ(store::historyStep("ibv_v"), 0.01);
  EXPECT_DOUBLE_EQ(store::historyStep("bcur_a"), 0.1);
  EXPECT_DOUBLE_EQ(store::historyStep("rpm"), 1.0);
  EXPECT_DOUBLE_EQ(store::historyStep("no_such_series"), 0.1);
}

// A v5 database (written before the ring and the int16 rows): the
// migration moves its float32 rows into the ring, where they read exactly; a
// flush into the same minute keeps them (quantised) beside the new samples,
// the row now in the int16 form; the old table is left empty.
TEST(HistoryEncoding, TheMigrationKeepsOldFloatRowsAndTheyMergeWithNewOnes) {
  TempDir d;
  StoreOptions opt;
  opt.historyFlushS = 60;
  const std::int64_t minuteS = (kT0 / 1000 / 60) * 60;
  {
    sql::Db db;
    ASSERT_EQ(db.open(d.file("x.db")), 0);
    ASSERT_EQ(store::createAtVersion(db, 5), SQLITE_OK);
    ASSERT_EQ(db.exec("INSERT INTO series(id, name) VALUES(0, 'ibv_v')"), SQLITE_OK);
    std::vector<float> old(store::kHistorySlots, NAN);
    for (int i = 0; i < 30; ++i) old[i] = 12.3456f + static_cast<float>(i);
    sql::Stmt ins(db, "INSERT INTO history_1s(key, data) VALUES(?1, ?2)");
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(old.data());
    for (std::int64_t m : {minuteS - 60, minuteS}) {  // two minutes in a row
      ins.reset();
      ASSERT_EQ(ins.bind(1, m * store::kSeriesSlots)
                    .bindBlob(2, std::span<const std::uint8_t>(bytes, store::kFloatRowBytes))
                    .step(),
                SQLITE_DONE);
    }
  }
  Store s(opt);
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  auto before = s.queryHistory("ibv_v", (minuteS - 60) * 1000, minuteS * 1000 + 59000, 0);
  ASSERT_EQ(before.size(), 60u);
  EXPECT_DOUBLE_EQ(before[0].value, static_cast<double>(12.3456f));  // the float row, exactly
  EXPECT_EQ(before[30].tMs, minuteS * 1000);
  std::vector<double> v(opt.historySeries.size(), 13.0);
  for (int sec = 30; sec < 60; ++sec) ASSERT_TRUE(s.appendHistory((minuteS + sec) * 1000, v).ok);
  ASSERT_TRUE(s.flushHistory().ok);
  auto after = s.queryHistory("ibv_v", minuteS * 1000, minuteS * 1000 + 59000, 0);
  ASSERT_EQ(after.size(), 60u);
  EXPECT_NEAR(after[0].value, 12.3456, 0.005);  // quantised to the 10 mV step
  EXPECT_NEAR(after[29].value, 41.3456, 0.005);
  EXPECT_NEAR(after[30].value, 13.0, 1e-4);
  s.close();
  sql::Db db;
  ASSERT_EQ(db.open(d.file("x.db")), 0);
  EXPECT_EQ(db.queryInt("PRAGMA user_version"), store::kSchemaVersion);
  EXPECT_EQ(db.queryInt("SELECT count(*) FROM history_1s"), 0);
  EXPECT_EQ(db.queryInt("SELECT length(data) FROM history_1s_ring WHERE t_s = " + std::to_string(minuteS)),
            static_cast<std::int64_t>(store::kInt16RowBytes));
  EXPECT_EQ(
      db.queryInt("SELECT length(data) FROM history_1s_ring WHERE t_s = " + std::to_string(minuteS - 60)),
      static_cast<std::int64_t>(store::kFloatRowBytes));
}

// A minute's slot comes round after kRingMinutes: the new minute replaces
// the old one in place, and a query for the old minute finds nothing.
TEST(HistoryEncoding, TheRingRewritesASlotAfterKRingMinutes) {
  TempDir d;
  StoreOptions opt;
  Store s(opt);
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  const std::int64_t minuteS = (kT0 / 1000 / 60) * 60;
  const std::int64_t laterS = minuteS + store::kRingMinutes * 60;
  std::vector<double> v(opt.historySeries.size(), 12.0);
  ASSERT_TRUE(s.appendHistory(minuteS * 1000, v).ok);
  ASSERT_TRUE(s.flushHistory().ok);
  v.assign(v.size(), 13.0);
  ASSERT_TRUE(s.appendHistory(laterS * 1000, v).ok);
  ASSERT_TRUE(s.flushHistory().ok);
  EXPECT_TRUE(s.queryHistory("ibv_v", minuteS * 1000, minuteS * 1000 + 59000, 0).empty());
  const auto now = s.queryHistory("ibv_v", laterS * 1000, laterS * 1000 + 59000, 0);
  ASSERT_EQ(now.size(), 1u);
  EXPECT_NEAR(now[0].value, 13.0, 1e-4);
  s.close();
  sql::Db db;
  ASSERT_EQ(db.open(d.file("x.db")), 0);
  EXPECT_EQ(db.queryInt("SELECT count(*) FROM history_1s_ring"), static_cast<std::int64_t>(v.size()));
}

}  // namespace
}  // namespace xr
