// The store's write windows (docs/performance.md "Storage writes"): the
// ledger's interval checkpoint falls on the wall clock's 5-minute marks, and
// at each 10-minute mark the chart flush, the day rows and the ledger are
// written in the same second (their commits share the WAL index pages); a
// stage change still saves the ledger at once.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "app/store_service.h"
#include "runtime/wall_clock.h"
#include "store/sqlite_db.h"
#include "store_test_util.h"

namespace xr::app {
namespace {

using xr::test::TempDir;

struct Rig {
  TempDir d;
  StoreService svc{d.file("x.db"), 300};
  TimeNs simulated = 0;
  rt::WallClock clock;
  rt::RuntimeSnapshot s;
  BatteryLedger ledger;
  // phaseMs: where in a 10-minute window of the wall clock the first second
  // falls, so a test does not depend on the time of day it runs at.
  explicit Rig(std::int64_t phaseMs = 0) {
    clock.followSimulation([this] { return simulated; });
    const std::int64_t behind = (phaseMs - clock.unixMs() % 600'000 + 600'000) % 600'000;
    simulated = fromSec(static_cast<double>(behind) / 1000.0);
    svc.useClock(clock, 1.0);
    s.tick = 1000;
    s.telemetry.field_enable = true;
    s.telemetry.stage = ChargeStage::FLOAT;
    s.telemetry.alt_a = 10.0;
    s.telemetry.battery_v = 13.5;
    s.telemetry.bcur_a = 4.0;
    s.telemetry.rpm = 1700.0;
  }
  // One housekeeping second; returns the clock's ms of it.
  std::int64_t second() {
    s.telemetry.now = simulated;
    ledger.CoulombCount_Ah += 0.001;
    const std::int64_t now = svc.clockMs();
    svc.housekeeping(s, ledger, true);
    simulated += fromSec(1.0);
    return now;
  }
};

TEST(StoreWriteWindows, TheIntervalCheckpointFallsOnTheFiveMinuteMarks) {
  Rig r;
  std::set<std::int64_t> saves;
  for (int i = 0; i < 21 * 60; ++i) {
    r.second();
    if (auto l = r.svc.loadLedger(); l && l->reason == "interval") saves.insert(l->savedAtMs);
  }
  ASSERT_GE(saves.size(), 4u);  // 21 minutes: four marks at least
  std::int64_t prev = -1;
  for (std::int64_t t : saves) {
    EXPECT_LT(t % 300'000, 1000) << t;  // the first second of a 5-minute mark
    if (prev >= 0) {
      EXPECT_EQ(t - prev, 300'000);
    }
    prev = t;
  }
  r.svc.stop(r.ledger, true);
}

// Whatever the time of day the service starts at (every 10 s of a 10-minute
// window, both sides of a mark), the first 10-minute mark a minute or more
// after the start writes the ledger, the chart's minute and the day row.
TEST(StoreWriteWindows, AtATenMinuteMarkTheChartDayRowsAndLedgerAreWrittenInTheSameSecond) {
  for (std::int64_t phase = 0; phase < 600'000; phase += 10'000) {
    SCOPED_TRACE("start at " + std::to_string(phase / 1000) + " s into the window");
    Rig r(phase);
    // A minute after the start, so the mark is not the start's own save of
    // the day rows and the chart holds the minute before it.
    const std::int64_t start = r.second();
    std::int64_t now = start;
    while (now % 600'000 >= 1000 || now - start < 61'000) now = r.second();
    const std::int64_t mark = now;
    sql::Db db;
    ASSERT_EQ(db.open(r.d.file("x.db")), 0);
    EXPECT_EQ(db.queryInt("SELECT saved_at_ms FROM ledger_meta"), mark);
    EXPECT_GT(
        db.queryInt("SELECT count(*) FROM history_1s_ring WHERE t_s = " + std::to_string(mark / 1000 - 60)),
        0);
    // And the day rows hold the seconds up to the mark: two rows when local
    // midnight falls between the start and the mark (the rig moves the
    // clock up to 10 minutes ahead, so a run in the day's last 10 minutes).
    const double fieldOnS =
        static_cast<double>(db.queryInt("SELECT CAST(SUM(field_on_s) AS INTEGER) FROM history_days"));
    EXPECT_GE(fieldOnS, 60.0);
    r.svc.stop(r.ledger, true);
  }
}

TEST(StoreWriteWindows, AStageChangeSavesTheLedgerAtOnceBetweenMarks) {
  Rig r;
  std::int64_t now = r.second();
  while (now % 300'000 < 60'000 || now % 300'000 > 200'000) now = r.second();  // between two marks
  r.s.telemetry.stage = ChargeStage::ABSORPTION;
  const std::int64_t changedAt = r.second();
  const auto l = r.svc.loadLedger();
  ASSERT_TRUE(l.has_value());
  EXPECT_EQ(l->reason, "stage");
  EXPECT_EQ(l->savedAtMs, changedAt);
  r.svc.stop(r.ledger, true);
}

// A wall clock that stands still (the intervals never change) still saves
// the ledger once an interval and a minute of monotonic time have passed.
TEST(StoreWriteWindows, AWallClockThatStandsStillStillSavesTheLedger) {
  Rig r;
  r.second();
  r.simulated -= fromSec(1.0);  // the wall clock stops here
  std::set<std::string> reasons;
  for (int i = 0; i < 7 * 60; ++i) {
    r.s.telemetry.now += fromSec(1.0);
    r.ledger.CoulombCount_Ah += 0.001;
    r.svc.housekeeping(r.s, r.ledger, true);
    if (auto l = r.svc.loadLedger()) reasons.insert(l->reason);
  }
  EXPECT_EQ(reasons.count("interval"), 1u);
  r.svc.stop(r.ledger, true);
}

}  // namespace
}  // namespace xr::app
