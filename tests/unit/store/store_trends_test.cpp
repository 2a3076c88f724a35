// Trends over a season and the History page's day rows at a glance
// (docs/dashboard.md "History", "Trends"): the hourly tally, its rows and
// the day rows summed from them in SQLite, their retention, and the v4 -> v5
// migration that keeps every row an older release wrote.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include "store/charge_tally.h"
#include "store/schema.h"
#include "store/store.h"
#include "store/trend_tally.h"
#include "store_test_util.h"

namespace xr {
namespace {

using test::kT0;
using test::TempDir;

constexpr std::int64_t kHourMs = 3'600'000;
const std::int64_t kHour0Ms = kT0 / kHourMs * kHourMs;  // an hour's start

TrendTally::Values values(double v, double a = 10.0) { return {v, a, 40.0, 70.0, NAN, 80.0}; }

TEST(TrendTally, AnHourEndsWithItsMinMeanAndMax) {
  TrendTally t;
  EXPECT_FALSE(t.add(kHour0Ms, 0, values(12.0)));
  EXPECT_FALSE(t.add(kHour0Ms + 1000, 0, values(14.0)));
  EXPECT_FALSE(t.add(kHour0Ms + kHourMs - 1, 0, values(13.0)));
  const auto row = t.add(kHour0Ms + kHourMs, 0, values(11.0));
  ASSERT_TRUE(row);
  EXPECT_EQ(row->startS, kHour0Ms / 1000);
  EXPECT_EQ(row->samples, 3);
  EXPECT_DOUBLE_EQ(row->stat[0].min, 12.0);
  EXPECT_DOUBLE_EQ(row->stat[0].mean, 13.0);
  EXPECT_DOUBLE_EQ(row->stat[0].max, 14.0);
  // No battery temperature sensor: not known, not zero.
  EXPECT_TRUE(std::isnan(row->stat[4].mean));
  EXPECT_EQ(t.current()->startS, kHour0Ms / 1000 + 3600);
  EXPECT_EQ(t.current()->samples, 1);
}

TEST(TrendTally, AReadingNotKnownIsLeftOutOfTheMean) {
  TrendTally t;
  t.add(kHour0Ms, 0, values(12.0));
  t.add(kHour0Ms + 1000, 0, values(NAN));
  EXPECT_DOUBLE_EQ(t.current()->stat[0].mean, 12.0);
  EXPECT_EQ(t.current()->samples, 2);
}

TEST(TrendTally, AClockSetBackEndsTheHour) {
  TrendTally t;
  t.add(kHour0Ms + 2 * kHourMs, 0, values(12.0));
  const auto row = t.add(kHour0Ms, 0, values(13.0));
  ASSERT_TRUE(row);
  EXPECT_EQ(row->startS, kHour0Ms / 1000 + 7200);
}

TrendRow hourRow(std::int64_t startS, std::int64_t dayS, std::int64_t samples, double vMin, double vMean,
                 double vMax) {
  TrendRow r;
  r.startS = startS;
  r.dayS = dayS;
  r.samples = samples;
  r.stat[0] = {vMin, vMean, vMax};
  return r;
}

TEST(StoreTrends, TheDayRowSumsItsHoursWeightedBySamples) {
  TempDir d;
  Store s;
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  const std::int64_t day = kHour0Ms / 1000;
  ASSERT_TRUE(s.saveTrendHour(hourRow(day, day, 3600, 12.5, 13.0, 14.4)).ok);
  ASSERT_TRUE(s.saveTrendHour(hourRow(day + 3600, day, 1200, 12.1, 12.2, 12.6)).ok);
  const auto hours = s.trends(day, day + 7200, false);
  ASSERT_EQ(hours.size(), 2u);
  EXPECT_DOUBLE_EQ(hours[1].stat[0].max, 12.6);
  EXPECT_TRUE(std::isnan(hours[1].stat[4].min));
  const auto days = s.trends(day, day, true);
  ASSERT_EQ(days.size(), 1u);
  EXPECT_EQ(days[0].samples, 4800);
  EXPECT_DOUBLE_EQ(days[0].stat[0].min, 12.1);
  EXPECT_DOUBLE_EQ(days[0].stat[0].max, 14.4);
  EXPECT_NEAR(days[0].stat[0].mean, (13.0 * 3600 + 12.2 * 1200) / 4800.0, 1e-12);
  EXPECT_TRUE(std::isnan(days[0].stat[4].mean));
  // The same hour saved again (a restart carried it on) replaces its row.
  ASSERT_TRUE(s.saveTrendHour(hourRow(day + 3600, day, 2400, 12.0, 12.2, 12.6)).ok);
  EXPECT_EQ(s.trends(day, day, true)[0].samples, 6000);
  EXPECT_EQ(s.findTrendHour(day + 3600)->samples, 2400);
}

TEST(StoreTrends, HoursAreKeptTwoYearsAndDaysLonger) {
  TempDir d;
  Store s;
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  const std::int64_t now = kT0 / 1000;
  const std::int64_t old = now - 732 * 86400, recent = now - 700 * 86400;
  ASSERT_TRUE(s.saveTrendHour(hourRow(old, old, 10, 12, 12, 12)).ok);
  ASSERT_TRUE(s.saveTrendHour(hourRow(recent, recent, 10, 13, 13, 13)).ok);
  ASSERT_TRUE(s.compact(kT0).ok);
  const auto hours = s.trends(0, now, false);
  ASSERT_EQ(hours.size(), 1u);
  EXPECT_EQ(hours[0].startS, recent);
  EXPECT_EQ(s.trends(0, now, true).size(), 2u);
}

TEST(StoreSummaries, ChargesOfADayAreThoseThatStartedInIt) {
  TempDir d;
  Store s;
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  for (std::int64_t startMs : {kT0 - 1, kT0, kT0 + 5000, kT0 + 86'400'000}) {
    ChargeSummary c;
    c.startMs = c.endMs = startMs;
    c.open = false;
    ASSERT_TRUE(s.saveCharge(c).ok);
  }
  const auto list = s.chargesBetween(kT0, kT0 + 86'400'000);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].startMs, kT0);
  EXPECT_EQ(list[1].startMs, kT0 + 5000);
}

TEST(ChargeTallyGlance, ADayKnowsItsVoltageRangeSocAtStartAndEndEnergyInAndEngineHours) {
  ChargeTally t;
  auto add = [&](std::int64_t i, double v, double a, double soc, bool engine) {
    TallySample x;
    x.unixMs = kT0 + i * 1000;
    x.day = "2026-07-01";
    x.batteryV = v;
    x.batteryA = a;
    x.socPct = soc;
    x.engineRunning = engine;
    t.add(x);
  };
  add(0, 12.6, -5.0, NAN, false);  // SoC not known yet at the day's start
  add(1, 12.4, -5.0, 60.0, false);
  for (int i = 2; i <= 3601; ++i) add(i, 14.2, 36.0, 61.0, true);
  add(3602, 0.0, 0.0, 90.0, false);  // a voltage of 0: no reading, not the day's lowest
  const DaySummary& d = t.day();
  EXPECT_DOUBLE_EQ(d.minBatteryV, 12.4);
  EXPECT_DOUBLE_EQ(d.maxBatteryV, 14.2);
  EXPECT_DOUBLE_EQ(d.socStartPct, 60.0);
  EXPECT_DOUBLE_EQ(d.socEndPct, 90.0);
  EXPECT_NEAR(d.engineS, 3600.0, 1e-9);
  EXPECT_NEAR(d.batteryWhIn, 36.0 * 14.2, 1e-6);  // 3600 s charging at 36 A, 14.2 V
}

TEST(Migration, FromV4KeepsTheDaysAndChargesNewFiguresUnknown) {
  TempDir d;
  {
    sql::Db db;
    ASSERT_EQ(db.open(d.file("x.db")), SQLITE_OK);
    ASSERT_EQ(store::createAtVersion(db, 4), SQLITE_OK) << db.lastError();
    ASSERT_EQ(
        db.exec("INSERT INTO history_days VALUES('2026-06-30', 80, 1100, 70, 20, 3600, 1800, 600, 0, 6000, "
                "71.5, 40, 95)"),
        SQLITE_OK);
    ASSERT_EQ(
        db.exec(
            "INSERT INTO history_charges(start_ms, end_ms, bulk_s, absorption_s, float_s, alt_ah, alt_wh, "
            "start_soc, end_soc, end_reason, open) VALUES(1782800000000, 1782806000000, 3600, 1800, 600, "
            "80, 1100, 40, 95, 'REASON_RPM_LOW', 0)"),
        SQLITE_OK);
  }
  Store s;
  const OpenResult r = s.open(d.file("x.db"), kT0);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.fromVersion, 4);
  const auto day = s.findDay("2026-06-30");
  ASSERT_TRUE(day);
  EXPECT_DOUBLE_EQ(day->altAh, 80.0);
  EXPECT_DOUBLE_EQ(day->peakAltTempC, 71.5);
  EXPECT_DOUBLE_EQ(day->maxSocPct, 95.0);
  EXPECT_TRUE(std::isnan(day->minBatteryV));
  EXPECT_TRUE(std::isnan(day->socStartPct));
  EXPECT_TRUE(std::isnan(day->engineS));
  const auto charges = s.charges(10);
  ASSERT_EQ(charges.size(), 1u);
  EXPECT_EQ(charges[0].endReason, "REASON_RPM_LOW");
  EXPECT_DOUBLE_EQ(charges[0].altWh, 1100.0);
  const std::int64_t h = kHour0Ms / 1000;
  EXPECT_TRUE(s.saveTrendHour(hourRow(h, h, 1, 13, 13, 13)).ok);
  EXPECT_EQ(s.integrityCheck(), "ok");
}

}  // namespace
}  // namespace xr
