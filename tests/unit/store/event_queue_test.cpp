// The event log's writes gathered (store/event_queue.h): at most one commit a
// second, a bound on what a power cut loses, and repeats of one kind thinned
// to a count; through the real store, what reaches the database.
#include "store/event_queue.h"

#include <gtest/gtest.h>

#include "store/store.h"
#include "store_test_util.h"

namespace xr {
namespace {

using test::kT0;
using test::TempDir;

EventRecord ev(std::int64_t tMs, const char* code = "ProtectionTrip", const char* level = "critical") {
  return {0, tMs, level, code, "REASON_TEMP_CRITICAL", "Field cut: alternator too hot", 201.0, 200.0};
}

TEST(EventQueue, TheFirstEventAfterAQuietSecondIsDueAtOnce) {
  EventQueue q;
  EXPECT_FALSE(q.due(kT0)) << "nothing queued";
  q.push(ev(kT0));
  EXPECT_TRUE(q.due(kT0));
  EXPECT_EQ(q.take(kT0, false).size(), 1u);
  q.written(kT0);
  EXPECT_EQ(q.pending(), 0u);
}

TEST(EventQueue, ABurstWaitsForTheNextSecondThenGoesInOneWrite) {
  EventQueue q;
  q.push(ev(kT0, "A"));
  ASSERT_EQ(q.take(kT0, false).size(), 1u);
  q.written(kT0);
  for (int i = 0; i < 4; ++i) q.push(ev(kT0 + 100 + i, i % 2 ? "B" : "C"));
  EXPECT_FALSE(q.due(kT0 + 999)) << "within the second of the last write";
  EXPECT_TRUE(q.due(kT0 + 1000)) << "a second after it: the bound a power cut can lose";
  const auto rows = q.take(kT0 + 1000, false);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_LE(rows.front().tMs, rows.back().tMs) << "oldest first";
}

TEST(EventQueue, AFullQueueIsDueWithinTheSecond) {
  EventQueueOptions o;
  o.maxPending = 8;
  o.repeatKept = 0;
  EventQueue q(o);
  q.push(ev(kT0));
  q.take(kT0, false);
  q.written(kT0);
  for (int i = 0; i < 7; ++i) q.push(ev(kT0 + 10));
  EXPECT_FALSE(q.due(kT0 + 10));
  q.push(ev(kT0 + 10));
  EXPECT_TRUE(q.due(kT0 + 10)) << "8 waiting";
}

TEST(EventQueue, AClockSetBackDoesNotHoldTheQueue) {
  EventQueue q;
  q.push(ev(kT0));
  q.take(kT0, false);
  q.written(kT0);
  q.push(ev(kT0 - 3'600'000, "B"));
  EXPECT_TRUE(q.due(kT0 - 3'600'000));
}

TEST(EventQueue, RepeatsOfOneKindAreKeptToTheLimitThenCountedInOneRow) {
  EventQueue q;  // 5 kept in 10 minutes
  std::vector<EventRecord> written;
  for (int i = 0; i < 20; ++i) {  // a trip every 30 s for 10 minutes
    q.push(ev(kT0 + i * 30'000LL));
    for (auto& r : q.take(kT0 + i * 30'000LL, false)) written.push_back(r);
  }
  EXPECT_EQ(written.size(), 5u) << "the first five, one by one";
  // The window ends: one summary row with the count and the latest values.
  const auto rows = q.take(kT0 + 600'000, false);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].code, "ProtectionTrip");
  EXPECT_EQ(rows[0].level, "critical");
  EXPECT_EQ(rows[0].tMs, kT0 + 19 * 30'000LL);
  EXPECT_NE(rows[0].message.find("and 15 more like it"), std::string::npos) << rows[0].message;
  // A new window keeps the next five again.
  q.push(ev(kT0 + 601'000));
  EXPECT_EQ(q.take(kT0 + 601'000, false).size(), 1u);
}

TEST(EventQueue, AtTheLimitNothingIsCountedAndOtherKindsAreNotThinned) {
  EventQueue q;
  for (int i = 0; i < 5; ++i) q.push(ev(kT0 + i));
  for (int i = 0; i < 7; ++i) q.push(ev(kT0 + i, "ProtectionClear", "info"));
  EXPECT_EQ(q.take(kT0 + 10, true).size(), 11u) << "5 trips (the limit: no summary) + 5 clears + 1 summary";
}

TEST(EventQueue, WhatAPersonDidIsNeverThinned) {
  EventQueue q;
  // An owner at the dashboard: many commands and settings changes in a minute.
  for (int i = 0; i < 8; ++i) q.push(ev(kT0 + i * 1000LL, "CommandApplied", "info"));
  for (int i = 0; i < 8; ++i) q.push(ev(kT0 + i * 1000LL + 1, "SettingsChanged", "info"));
  const auto rows = q.take(kT0 + 60'000, true);
  EXPECT_EQ(rows.size(), 16u) << "every command and change its own row, no summary";
  for (const auto& r : rows) EXPECT_EQ(r.message.find("more like it"), std::string::npos) << r.message;
}

TEST(EventQueue, ClosingWritesTheCountOfAWindowStillOpen) {
  EventQueue q;
  for (int i = 0; i < 9; ++i) q.push(ev(kT0 + i * 1000LL));
  EXPECT_EQ(q.take(kT0 + 9000, false).size(), 5u);
  const auto rows = q.take(kT0 + 9000, true);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NE(rows[0].message.find("and 4 more like it"), std::string::npos) << rows[0].message;
}

TEST(StoreEventQueue, AStormIsWrittenInFewCommitsAndAQueryShowsWhatIsQueued) {
  TempDir d;
  const std::string db = d.file("x.db");
  {
    Store s;
    ASSERT_TRUE(s.open(db, kT0).ok);
    ASSERT_TRUE(s.queueEvent(ev(kT0, "StoreSaved", "info"), kT0).ok);
    EXPECT_EQ(s.queryEvents(10).size(), 1u);
    // Ten events within the second: queued, yet a query sees them.
    for (int i = 0; i < 10; ++i) ASSERT_TRUE(s.queueEvent(ev(kT0 + 100, "ProtectionTrip"), kT0 + 100).ok);
    EXPECT_EQ(s.queryEvents(100).size(), 6u) << "1 + the first 5 trips; 5 counted";
    // Ten minutes on, the count is written as one row.
    ASSERT_TRUE(s.flushEventsIfDue(kT0 + 600'100).ok);
    const auto all = s.queryEvents(100);
    ASSERT_EQ(all.size(), 7u);
    EXPECT_NE(all.front().message.find("and 5 more like it"), std::string::npos) << all.front().message;
    ASSERT_TRUE(s.queueEvent(ev(kT0 + 700'000, "Other"), kT0 + 700'000).ok);
    ASSERT_TRUE(s.queueEvent(ev(kT0 + 700'010, "Other2"), kT0 + 700'010).ok);  // waits for the second
  }                                                                            // closing writes what waits
  Store again;
  ASSERT_TRUE(again.open(db, kT0 + 800'000).ok);
  EXPECT_EQ(again.queryEvents(100).size(), 9u);
}

}  // namespace
}  // namespace xr
