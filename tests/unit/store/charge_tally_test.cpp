// The History page's day and charge summaries (store/charge_tally.h), from
// one sample a second as the store service feeds them, and their rows in
// SQLite (store/store_summaries.cpp).
#include "store/charge_tally.h"

#include <gtest/gtest.h>

#include "store/store.h"
#include "store_test_util.h"

namespace xr {
namespace {

using test::kT0;
using test::TempDir;

struct Feed {
  ChargeTally tally;
  std::int64_t t = kT0;
  std::string day = "2026-07-01";
  ChargeTally::Ended last;
  // n samples a second apart.
  void run(int n, bool fieldOn, ChargeStage stage = ChargeStage::BULK, double altA = 50.0,
           Reason reason = Reason::NONE) {
    for (int i = 0; i < n; ++i) {
      TallySample s;
      s.unixMs = t;
      s.day = day;
      s.altA = fieldOn ? altA : 0.0;
      s.batteryV = 14.0;
      s.batteryA = fieldOn ? altA - 10.0 : -10.0;
      s.altTempC = 60.0 + i % 7;
      s.socPct = 50.0;
      s.stage = stage;
      s.fieldOn = fieldOn;
      s.reason = reason;
      last = tally.add(s);
      if (last.charge) ended = last.charge;
      t += 1000;
    }
  }
  std::optional<ChargeSummary> ended;
};

TEST(ChargeTally, ADayCountsTheAlternatorsAmpHoursAndTheHoursInEachStage) {
  Feed f;
  f.run(1800, true, ChargeStage::BULK);
  f.run(1800, true, ChargeStage::ABSORPTION);
  const DaySummary& d = f.tally.day();
  EXPECT_EQ(d.day, "2026-07-01");
  EXPECT_NEAR(d.altAh, 50.0 * 3599.0 / 3600.0, 1e-9);  // the first sample starts the clock
  EXPECT_NEAR(d.altWh, 700.0 * 3599.0 / 3600.0, 1e-6);
  EXPECT_DOUBLE_EQ(d.bulkS, 1799.0);
  EXPECT_DOUBLE_EQ(d.absorptionS, 1800.0);
  EXPECT_DOUBLE_EQ(d.fieldOnS, 3599.0);
  EXPECT_NEAR(d.batteryAhIn, 40.0 * 3599.0 / 3600.0, 1e-9);
  EXPECT_DOUBLE_EQ(d.peakAltTempC, 66.0);
}

TEST(ChargeTally, ADayEndsWhenTheCalendarDayChanges) {
  Feed f;
  f.run(60, true);
  EXPECT_FALSE(f.last.day);
  f.day = "2026-07-02";
  f.run(1, true);
  ASSERT_TRUE(f.last.day);
  EXPECT_EQ(f.last.day->day, "2026-07-01");
  EXPECT_DOUBLE_EQ(f.last.day->fieldOnS, 59.0);
  EXPECT_EQ(f.tally.day().day, "2026-07-02");
  EXPECT_DOUBLE_EQ(f.tally.day().fieldOnS, 1.0);
}

TEST(ChargeTally, AFieldOffShorterThanFiveMinutesDoesNotEndTheCharge) {
  Feed f;
  f.run(600, true);
  f.run(299, false, ChargeStage::BULK, 0.0, Reason::REASON_TEMP_WARNING);
  f.run(600, true);
  EXPECT_FALSE(f.ended);
  ASSERT_TRUE(f.tally.charge());
  EXPECT_NEAR(f.tally.charge()->bulkS, 1198.0 + 1.0, 1.0);  // both field-on stretches
}

TEST(ChargeTally, FiveMinutesOffEndsTheChargeWithTheReasonItStoppedFor) {
  Feed f;
  f.run(600, true, ChargeStage::BULK);
  f.run(300, true, ChargeStage::ABSORPTION);
  const std::int64_t lastOn = f.t - 1000;
  f.run(1, false, ChargeStage::ABSORPTION, 0.0, Reason::REASON_RPM_LOW);
  f.run(298, false, ChargeStage::ABSORPTION, 0.0, Reason::NONE);
  EXPECT_FALSE(f.ended) << "ended after 299 s off";
  f.run(2, false, ChargeStage::ABSORPTION, 0.0, Reason::NONE);
  ASSERT_TRUE(f.ended);
  EXPECT_FALSE(f.ended->open);
  EXPECT_EQ(f.ended->endReason, "REASON_RPM_LOW");
  EXPECT_EQ(f.ended->startMs, kT0);
  EXPECT_EQ(f.ended->endMs, lastOn);
  EXPECT_DOUBLE_EQ(f.ended->absorptionS, 300.0);
  EXPECT_NEAR(f.ended->altAh, 50.0 * 899.0 / 3600.0, 1e-9);
  EXPECT_FALSE(f.tally.charge());
}

TEST(ChargeTally, AGapOrAClockSetBackIsNotCounted) {
  Feed f;
  f.run(10, true);
  f.t += 10'000;  // 10 s with no sample: the daemon was stopped
  f.run(1, true);
  EXPECT_DOUBLE_EQ(f.tally.day().fieldOnS, 9.0);
  f.t -= 3'600'000;  // the clock set back an hour
  f.run(1, true);
  EXPECT_DOUBLE_EQ(f.tally.day().fieldOnS, 9.0);
}

TEST(ChargeTally, AnUnknownSocOrTemperatureIsNotANumber) {
  ChargeTally t;
  TallySample s;
  s.unixMs = kT0;
  s.day = "2026-07-01";
  t.add(s);
  EXPECT_TRUE(std::isnan(t.day().peakAltTempC));
  EXPECT_TRUE(std::isnan(t.day().minSocPct));
  s.unixMs += 1000;
  s.socPct = 71.0;
  t.add(s);
  EXPECT_DOUBLE_EQ(t.day().minSocPct, 71.0);
}

TEST(StoreSummaries, DaysAndChargesRoundTripNewestFirst) {
  TempDir d;
  Store s;
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  DaySummary a;
  a.day = "2026-07-01";
  a.altAh = 12.5;
  DaySummary b = a;
  b.day = "2026-07-02";
  b.peakAltTempC = 88.0;
  ASSERT_TRUE(s.saveDay(a).ok);
  ASSERT_TRUE(s.saveDay(b).ok);
  b.altAh = 20.0;
  ASSERT_TRUE(s.saveDay(b).ok);  // the same day again: replaced
  const auto days = s.days(30);
  ASSERT_EQ(days.size(), 2u);
  EXPECT_EQ(days[0].day, "2026-07-02");
  EXPECT_DOUBLE_EQ(days[0].altAh, 20.0);
  EXPECT_DOUBLE_EQ(days[0].peakAltTempC, 88.0);
  EXPECT_TRUE(std::isnan(days[1].peakAltTempC));
  ASSERT_TRUE(s.findDay("2026-07-01"));
  EXPECT_FALSE(s.findDay("2026-06-30"));

  ChargeSummary c;
  c.startMs = kT0;
  c.endMs = kT0 + 60'000;
  ASSERT_TRUE(s.saveCharge(c).ok);
  EXPECT_GT(c.id, 0);
  c.altAh = 3.0;
  ASSERT_TRUE(s.saveCharge(c).ok);  // updated, not a second row
  ChargeSummary later = c;
  later.id = 0;
  later.startMs = kT0 + 3'600'000;
  ASSERT_TRUE(s.saveCharge(later).ok);
  ASSERT_TRUE(s.closeOpenCharges("STOPPED").ok);
  const auto charges = s.charges(20);
  ASSERT_EQ(charges.size(), 2u);
  EXPECT_EQ(charges[0].id, later.id);
  EXPECT_DOUBLE_EQ(charges[1].altAh, 3.0);
  EXPECT_FALSE(charges[0].open);
  EXPECT_EQ(charges[0].endReason, "STOPPED");
}

}  // namespace
}  // namespace xr
