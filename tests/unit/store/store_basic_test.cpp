// Store: ledger, overrides, events, history, token.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

#include "store/param_overrides.h"
#include "store/schema.h"
#include "store/store.h"
#include "store_test_util.h"

namespace xr {
namespace {

using test::kT0;
using test::TempDir;

BatteryLedger sampleLedger() {
  BatteryLedger l;
  double v = 1.25;
  visitLedgerFields(l, [&](const char*, double& f) { f = (v *= 1.7); });
  l.valid = true;
  return l;
}

TEST(Store, CreatesWalDatabaseAtCurrentSchema) {
  TempDir d;
  Store s;
  const OpenResult r = s.open(d.file("sub/dir/x.db"), kT0);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_FALSE(r.alarm());
  sql::Db db;
  ASSERT_EQ(db.open(d.file("sub/dir/x.db")), 0);
  EXPECT_EQ(db.queryText("PRAGMA journal_mode"), "wal");
  EXPECT_EQ(db.queryInt("PRAGMA user_version"), store::kSchemaVersion);
}

TEST(Store, LedgerRoundTripWithTimeAndReason) {
  TempDir d;
  const BatteryLedger l = sampleLedger();
  {
    Store s;
    ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
    EXPECT_FALSE(s.loadLedger().has_value());  // nothing saved yet
    ASSERT_TRUE(s.checkpoint(l, "field_off", kT0 + 5000).ok);
  }
  Store s;
  ASSERT_TRUE(s.open(d.file("x.db"), kT0 + 10000).ok);
  const auto saved = s.loadLedger();
  ASSERT_TRUE(saved.has_value());
  EXPECT_EQ(saved->ledger, l);
  EXPECT_EQ(saved->savedAtMs, kT0 + 5000);
  EXPECT_EQ(saved->reason, "field_off");
}

TEST(Store, OverridesSurviveRestartAndFileValueReturnsAfterReset) {
  TempDir d;
  const Params file;  // the TOML file's values
  Params operatorSet = file;
  operatorSet.BulkVoltage = 14.2;
  operatorSet.rpmCapCurrentTable[3] = 42.5;
  {
    Store s;
    ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
    ASSERT_TRUE(saveParamOverride(s, "BulkVoltage", file, operatorSet, kT0).ok);
    ASSERT_TRUE(saveParamOverride(s, "rpmCapCurrentTable", file, operatorSet, kT0).ok);
    EXPECT_FALSE(saveParamOverride(s, "NoSuchParam", file, operatorSet, kT0).ok);
  }
  {
    Store s;
    ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
    const auto rows = s.overrides();
    ASSERT_EQ(rows.size(), 2u);
    const auto bulk = s.findOverride("BulkVoltage");
    ASSERT_TRUE(bulk.has_value());
    EXPECT_EQ(bulk->value, "14.2");
    EXPECT_EQ(bulk->fileValue, "14.5");  // shown as "changed from 14.5"
    std::vector<std::string> errors;
    const Params applied = applyStoredOverrides(file, rows, errors);
    EXPECT_TRUE(errors.empty());
    EXPECT_EQ(applied, operatorSet);
    ASSERT_TRUE(s.resetOverride("BulkVoltage").ok);
  }
  Store s;
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  std::vector<std::string> errors;
  const Params applied = applyStoredOverrides(file, s.overrides(), errors);
  EXPECT_DOUBLE_EQ(applied.BulkVoltage, file.BulkVoltage);  // the file value is back
  EXPECT_DOUBLE_EQ(applied.rpmCapCurrentTable[3], 42.5);    // the other override stays
}

TEST(Store, BadStoredOverridesAreSkippedNotApplied) {
  const Params file;
  std::vector<OverrideRow> rows{{"BulkVoltage", "999", "14.5", 0},
                                {"Gone", "1", "1", 0},
                                {"rpmCapCurrentTable", "1,2,3", "", 0},
                                {"FloatVoltage", "13.2", "13.5", 0}};
  std::vector<std::string> errors;
  const Params p = applyStoredOverrides(file, rows, errors);
  EXPECT_EQ(errors.size(), 3u);
  EXPECT_DOUBLE_EQ(p.BulkVoltage, file.BulkVoltage);
  EXPECT_EQ(p.rpmCapCurrentTable, file.rpmCapCurrentTable);
  EXPECT_DOUBLE_EQ(p.FloatVoltage, 13.2);
}

TEST(Store, EventsNewestFirstWithLimitAndBefore) {
  TempDir d;
  Store s;
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  std::vector<EventRecord> evs;
  for (int i = 0; i < 30; ++i) {
    Event e;
    e.level = EventLevel::Warning;
    e.code = EventCode::FullChargeDetected;
    e.a = i;
    evs.push_back(toEventRecord(e, kT0 + i * 1000));
  }
  ASSERT_TRUE(s.appendEvents(evs).ok);
  const auto last10 = s.queryEvents(10);
  ASSERT_EQ(last10.size(), 10u);
  EXPECT_EQ(last10.front().tMs, kT0 + 29000);
  EXPECT_EQ(last10.back().tMs, kT0 + 20000);
  EXPECT_EQ(last10.front().code, "FullChargeDetected");
  EXPECT_EQ(last10.front().level, toString(EventLevel::Warning));
  EXPECT_DOUBLE_EQ(last10.front().a, 29.0);
  EXPECT_FALSE(last10.front().message.empty());
  const auto page2 = s.queryEvents(10, last10.back().tMs);
  ASSERT_EQ(page2.size(), 10u);
  EXPECT_EQ(page2.front().tMs, kT0 + 19000);
  const auto byId = s.queryEventsBeforeId(5, last10.back().id);
  ASSERT_EQ(byId.size(), 5u);
  EXPECT_EQ(byId.front().id, last10.back().id - 1);
  EXPECT_EQ(byId.front().tMs, kT0 + 19000);
  EXPECT_TRUE(s.queryEventsBeforeId(5, byId.back().id - 15).empty());
}

TEST(Store, HistoryOneSecondAndOneMinute) {
  TempDir d;
  StoreOptions opt;
  opt.historyFlushS = 120;
  Store s(opt);
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  const std::size_t n = opt.historySeries.size();
  const std::int64_t t0 = (kT0 / 3600000) * 3600000;  // an hour boundary
  // 10 minutes of samples: soc_pct = minute index, ibv_v = seconds.
  for (int sec = 0; sec < 600; ++sec) {
    std::vector<double> v(n, NAN);
    v[0] = sec;
    v[3] = sec / 60;
    ASSERT_TRUE(s.appendHistory(t0 + sec * 1000LL, v).ok);
  }
  // Raw 1 s points, half from the database, half still buffered.
  auto raw = s.queryHistory("ibv_v", t0 + 100000, t0 + 399000, 0);
  ASSERT_EQ(raw.size(), 300u);
  EXPECT_DOUBLE_EQ(raw.front().value, 100.0);
  EXPECT_EQ(raw.back().tMs, t0 + 399000);
  // 10 s bins average.
  auto bins = s.queryHistory("ibv_v", t0, t0 + 59999, 10000);
  ASSERT_EQ(bins.size(), 6u);
  EXPECT_DOUBLE_EQ(bins[1].value, 14.5);
  // The 1 min table holds each finished minute's mean.
  ASSERT_TRUE(s.flushHistory().ok);
  auto minutes = s.queryHistory("soc_pct", t0, t0 + 3600000, 60000);
  ASSERT_EQ(minutes.size(), 9u);  // the 10th minute is still being averaged
  for (std::size_t i = 0; i < minutes.size(); ++i) EXPECT_DOUBLE_EQ(minutes[i].value, static_cast<double>(i));
  auto ibvMin = s.queryHistory("ibv_v", t0, t0 + 3600000, 60000);
  ASSERT_FALSE(ibvMin.empty());
  EXPECT_DOUBLE_EQ(ibvMin[0].value, 29.5);
  EXPECT_TRUE(s.queryHistory("no_such_series", t0, t0 + 1000, 0).empty());
  // Survives a restart.
  s.close();
  Store s2(opt);
  ASSERT_TRUE(s2.open(d.file("x.db"), kT0).ok);
  EXPECT_EQ(s2.queryHistory("ibv_v", t0, t0 + 599000, 0).size(), 600u);
}

// The 1 s chart is a ring of kRingMinutes minutes (48 h and one to spare):
// after 50 h it holds no more rows than that, the oldest 49 h old, and the
// newest 48 h still read back; the 1 min table is trimmed to its keep.
TEST(Store, HistoryRetentionIsBounded) {
  TempDir d;
  StoreOptions opt;
  opt.history1mKeepS = 7200;  // shortened, same mechanism
  Store s(opt);
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  const std::size_t n = opt.historySeries.size();
  const std::int64_t t0 = (kT0 / 3600000) * 3600000;
  const int hours = 50;
  std::vector<double> v(n, 1.0);
  for (int sec = 0; sec < hours * 3600; sec += 30) ASSERT_TRUE(s.appendHistory(t0 + sec * 1000LL, v).ok);
  ASSERT_TRUE(s.flushHistory().ok);
  ASSERT_TRUE(s.compact(t0 + hours * 3600 * 1000LL).ok);
  const std::int64_t endS = t0 / 1000 + hours * 3600;
  EXPECT_EQ(s.queryHistory("ibv_v", (endS - 47 * 3600) * 1000, endS * 1000, 0).size(), 47u * 120u);
  s.close();
  sql::Db db;
  ASSERT_EQ(db.open(d.file("x.db")), 0);
  const std::int64_t rows1s = db.queryInt("SELECT count(*) FROM history_1s_ring");
  const std::int64_t oldest1s = db.queryInt("SELECT min(t_s) FROM history_1s_ring");
  const std::int64_t oldest1m = db.queryInt("SELECT min(key) FROM history_1m") / store::kSeriesSlots;
  ASSERT_GT(oldest1m, 0);
  EXPECT_EQ(rows1s, static_cast<std::int64_t>(n) * store::kRingMinutes);
  EXPECT_EQ(oldest1s, endS - store::kRingMinutes * 60);
  EXPECT_GE(oldest1m, endS - 7200 - 3600);
  EXPECT_EQ(db.queryInt("SELECT count(*) FROM history_1s"), 0);
}

TEST(Store, EventsBounded) {
  TempDir d;
  StoreOptions opt;
  opt.maxEvents = 100;
  Store s(opt);
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  std::vector<EventRecord> evs(250);
  for (int i = 0; i < 250; ++i) evs[i] = EventRecord{0, kT0 + i, "Info", "Message", "NONE", "m", 0, 0};
  ASSERT_TRUE(s.appendEvents(evs).ok);
  ASSERT_TRUE(s.compact(kT0 + 1000).ok);
  const auto all = s.queryEvents(1000);
  EXPECT_EQ(all.size(), 100u);
  EXPECT_EQ(all.front().tMs, kT0 + 249);
}

TEST(Store, NonFiniteValuesDoNotCostTheWrite) {
  TempDir d;
  Store s;
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  BatteryLedger l = sampleLedger();
  ASSERT_TRUE(s.checkpoint(l, "interval", kT0).ok);
  BatteryLedger bad = l;
  bad.ChargedEnergy_AllTime_Wh += 10.0;
  bad.CoulombCount_Ah = NAN;
  ASSERT_TRUE(s.checkpoint(bad, "interval", kT0 + 1).ok);
  const auto saved = s.loadLedger();
  ASSERT_TRUE(saved.has_value());
  EXPECT_DOUBLE_EQ(saved->ledger.ChargedEnergy_AllTime_Wh, bad.ChargedEnergy_AllTime_Wh);
  EXPECT_DOUBLE_EQ(saved->ledger.CoulombCount_Ah, l.CoulombCount_Ah);  // last good value kept
  EventRecord e{0, kT0, "warning", "ProtectionTrip", "NONE", "stale", NAN, INFINITY};
  ASSERT_TRUE(s.appendEvents(std::span<const EventRecord>(&e, 1)).ok);
  EXPECT_EQ(s.queryEvents(1).at(0).message, "stale");
}

TEST(Store, TokenCreatedOnceAndKept) {
  TempDir d;
  std::string tok;
  {
    Store s;
    ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
    tok = s.getOrCreateToken();
    EXPECT_EQ(tok.size(), 64u);
    EXPECT_EQ(s.getOrCreateToken(), tok);
  }
  Store s;
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  EXPECT_EQ(s.getOrCreateToken(), tok);
  TempDir d2;
  Store other;
  ASSERT_TRUE(other.open(d2.file("y.db"), kT0).ok);
  EXPECT_NE(other.getOrCreateToken(), tok);
}

TEST(Store, BlobsForTuningLogs) {
  TempDir d;
  Store s;
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  EXPECT_FALSE(s.getBlob("tuning_log").has_value());
  ASSERT_TRUE(s.putBlob("tuning_log", R"({"entries":[1,2]})").ok);
  ASSERT_TRUE(s.putBlob("tuning_log", R"({"entries":[3]})").ok);
  EXPECT_EQ(s.getBlob("tuning_log").value(), R"({"entries":[3]})");
}

}  // namespace
}  // namespace xr

namespace xr {
namespace {

TEST(Store, ConcurrentWriterAndReaders) {
  test::TempDir d;
  StoreOptions opt;
  opt.historyFlushS = 10;
  Store s(opt);
  ASSERT_TRUE(s.open(d.file("x.db"), test::kT0).ok);
  std::atomic<bool> done{false};
  std::atomic<int> reads{0};
  std::thread reader([&] {
    while (!done.load()) {
      s.queryEvents(20);
      s.queryHistory("ibv_v", test::kT0, test::kT0 + 600000, 10000);
      s.overrides();
      ++reads;
    }
  });
  std::vector<double> v(opt.historySeries.size(), 12.5);
  for (int i = 0; i < 600; ++i) {
    ASSERT_TRUE(s.appendHistory(test::kT0 + i * 1000LL, v).ok);
    EventRecord e{0, test::kT0 + i, "info", "Message", "NONE", "m", 0, 0};
    ASSERT_TRUE(s.appendEvents(std::span<const EventRecord>(&e, 1)).ok);
  }
  while (reads.load() == 0) std::this_thread::yield();  // at least one overlapping read pass
  done = true;
  reader.join();
  EXPECT_EQ(s.queryEvents(1000).size(), 600u);
  EXPECT_EQ(s.queryHistory("ibv_v", test::kT0, test::kT0 + 599000, 0).size(), 600u);
  EXPECT_EQ(s.integrityCheck(), "ok");
}

}  // namespace
}  // namespace xr
