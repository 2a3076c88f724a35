// What the daily verified copy holds (docs/performance.md "Storage writes"):
// everything of the owner's that running cannot make again (settings, the
// ledger, the token, events, the History page's days and charges, the daily
// trend rows), and not the chart history and hourly trends, which are most
// of the file. A restore from it brings back every row it promises.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "store/backup.h"
#include "store/store.h"
#include "store_test_util.h"

namespace xr {
namespace {

using test::kT0;
using test::TempDir;
namespace fs = std::filesystem;

constexpr std::int64_t kDayMs = 24 * 3600 * 1000LL;

TrendRow trendRow(std::int64_t startS, std::int64_t dayS, double v) {
  TrendRow r;
  r.startS = startS;
  r.dayS = dayS;
  r.samples = 3600;
  for (auto& s : r.stat) s = {v - 1, v, v + 1};
  return r;
}

// A month of an owner's data: settings, ledger, token, events, days,
// charges, trends, and a day of 1 s chart history (the bulk of the file).
struct Owner {
  std::string token;
  std::int64_t chargeId = 0;
  std::int64_t day0S = 0;
};

Owner fill(Store& s) {
  Owner o;
  EXPECT_TRUE(s.setOverride("FloatVoltage", "13.4", "13.5", kT0).ok);
  BatteryLedger l;
  l.ChargedEnergy_AllTime_Wh = 98765.5;
  EXPECT_TRUE(s.checkpoint(l, "stop", kT0).ok);
  o.token = s.getOrCreateToken();
  std::vector<EventRecord> evs;
  for (int i = 0; i < 200; ++i)
    evs.push_back({0, kT0 + i * 1000LL, "warning", "ProtectionTrip", "REASON_TEMP_CRITICAL", "hot", 1, 2});
  EXPECT_TRUE(s.appendEvents(evs).ok);
  DaySummary d;
  d.day = "2023-11-14";
  d.altAh = 123.0;
  d.socStartPct = 55.0;
  EXPECT_TRUE(s.saveDay(d).ok);
  ChargeSummary c;
  c.startMs = kT0;
  c.endMs = kT0 + 3'600'000;
  c.altAh = 80.0;
  c.endReason = "REASON_RPM_LOW";
  c.open = false;
  EXPECT_TRUE(s.saveCharge(c).ok);
  o.chargeId = c.id;
  o.day0S = kT0 / 1000 / 86400 * 86400;
  for (int h = 0; h < 24 * 30; ++h)
    EXPECT_TRUE(s.saveTrendHour(trendRow(o.day0S + h * 3600LL, o.day0S + h / 24 * 86400LL, 12.0 + h % 3)).ok);
  std::vector<double> v(defaultHistorySeries().size(), 13.1);
  for (int sec = 0; sec < 86400; ++sec) EXPECT_TRUE(s.appendHistory(kT0 + sec * 1000LL, v).ok);
  EXPECT_TRUE(s.flushHistory().ok);
  return o;
}

TEST(StoreBackupContents, TheDailyCopyLeavesOutTheChartsAndIsAFractionOfTheFile) {
  TempDir dir;
  const std::string db = dir.file("x.db");
  Store s;
  ASSERT_TRUE(s.open(db, kT0).ok);
  fill(s);
  ASSERT_TRUE(s.backup(kT0 + 2 * kDayMs).ok);
  s.close();  // the WAL folded into the file: its size is the data's
  const auto dbBytes = fs::file_size(db), bakBytes = fs::file_size(db + ".bak");
  EXPECT_GT(dbBytes, 1'000'000u) << "a day of 1 s history";
  EXPECT_LT(bakBytes * 10, dbBytes) << "the copy is " << bakBytes << " B of a " << dbBytes << " B file";
  EXPECT_FALSE(fs::exists(db + ".bak-wal")) << "one self-contained file";
}

TEST(StoreBackupContents, ARestoreBringsBackEverySettingAndHistoryRowItPromises) {
  TempDir dir;
  const std::string db = dir.file("x.db");
  Owner o;
  {
    Store s;
    ASSERT_TRUE(s.open(db, kT0).ok);
    o = fill(s);
    ASSERT_TRUE(s.backup(kT0 + 2 * kDayMs).ok);
  }
  // The card loses the file.
  for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(db + suffix);
  Store s;
  const OpenResult r = s.open(db, kT0 + 3 * kDayMs);
  ASSERT_TRUE(r.ok && r.restored) << r.message;
  EXPECT_NE(r.message.find("the charts and hourly trends, not in the copy, start again"), std::string::npos)
      << r.message;
  ASSERT_TRUE(s.findOverride("FloatVoltage").has_value());
  EXPECT_EQ(s.findOverride("FloatVoltage")->value, "13.4");
  ASSERT_TRUE(s.loadLedger().has_value());
  EXPECT_DOUBLE_EQ(s.loadLedger()->ledger.ChargedEnergy_AllTime_Wh, 98765.5);
  EXPECT_EQ(s.getOrCreateToken(), o.token);
  const auto events = s.queryEvents(1000);
  // 200 of the owner's; the restore's own alarm is added by the service, not here.
  EXPECT_EQ(events.size(), 200u);
  const auto day = s.findDay("2023-11-14");
  ASSERT_TRUE(day.has_value());
  EXPECT_DOUBLE_EQ(day->altAh, 123.0);
  EXPECT_DOUBLE_EQ(day->socStartPct, 55.0);
  const auto charges = s.charges(10);
  ASSERT_EQ(charges.size(), 1u);
  EXPECT_EQ(charges[0].id, o.chargeId);
  EXPECT_DOUBLE_EQ(charges[0].altAh, 80.0);
  EXPECT_EQ(charges[0].endReason, "REASON_RPM_LOW");
  const auto daily = s.trends(o.day0S, o.day0S + 40 * 86400LL, true);
  EXPECT_EQ(daily.size(), 30u) << "the daily trend rows are the season's record";
  EXPECT_TRUE(s.trends(o.day0S, o.day0S + 40 * 86400LL, false).empty()) << "hourly rows are not copied";
  EXPECT_TRUE(s.queryHistory("ibv_v", kT0, kT0 + 2 * kDayMs, 60000).empty()) << "chart history is not copied";
  // A working database again: new rows of every kind are written.
  std::vector<double> v(defaultHistorySeries().size(), 12.9);
  ASSERT_TRUE(s.appendHistory(kT0 + 3 * kDayMs, v).ok);
  ASSERT_TRUE(s.flushHistory().ok);
  EXPECT_EQ(s.queryHistory("ibv_v", kT0 + 3 * kDayMs - 1000, kT0 + 3 * kDayMs + 1000, 0).size(), 1u);
  ASSERT_TRUE(s.saveTrendHour(trendRow(o.day0S + 40 * 86400LL, o.day0S + 40 * 86400LL, 13.0)).ok);
  EXPECT_EQ(s.integrityCheck(), "ok");
}

TEST(StoreBackupContents, TheCopyBeforeAMigrationStaysWhole) {
  // A downgrade must find the old release's charts too: the copy made before
  // a migration (.bak-v<N>) is page for page (store_backup_test.cpp shows it
  // is made); here, that the daily copy's thinning is not applied to it.
  TempDir dir;
  const std::string db = dir.file("x.db");
  Store s;
  ASSERT_TRUE(s.open(db, kT0).ok);
  std::vector<double> v(defaultHistorySeries().size(), 13.1);
  for (int sec = 0; sec < 600; ++sec) ASSERT_TRUE(s.appendHistory(kT0 + sec * 1000LL, v).ok);
  ASSERT_TRUE(s.flushHistory().ok);
  sql::Db raw;
  ASSERT_EQ(raw.open(db), 0);
  const std::string path = dir.file("whole.bak");
  ASSERT_EQ(store::writeVerifiedBackup(raw, path, 0600), "");
  Store copy;
  ASSERT_TRUE(copy.open(path, kT0 + 1000).ok);
  EXPECT_EQ(copy.queryHistory("ibv_v", kT0, kT0 + 599000, 0).size(), 600u);
}

}  // namespace
}  // namespace xr
