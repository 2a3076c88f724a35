// StoreService: the store thread's loop (checkpoints by policy, history at
// 1 Hz, events, restore on start, error reporting once per failure streak).
#include "store/store_service.h"

#include <gtest/gtest.h>

#include <vector>

#include "store_test_util.h"

namespace xr {
namespace {

using test::kT0;
using test::TempDir;
constexpr TimeNs S = 1'000'000'000;

struct Reports {
  std::vector<std::pair<EventLevel, std::string>> items;
  StoreService::Report fn() {
    return [this](EventLevel l, const std::string& m) { items.emplace_back(l, m); };
  }
};

TEST(StoreService, RunCheckpointsRestoresAndReports) {
  TempDir d;
  StoreSettings st;
  st.path = d.file("state/x.db");
  st.checkpoint_interval_s = 300;
  BatteryLedger l;
  l.valid = true;
  Reports rep;
  {
    StoreService svc(st, {}, rep.fn());
    const StoreStart s0 = svc.start(kT0);
    EXPECT_FALSE(s0.alarm);
    EXPECT_FALSE(s0.restored.has_value());
    EXPECT_NE(s0.message.find("no saved ledger"), std::string::npos);
    Telemetry t;
    t.field_enable = true;
    t.stage = ChargeStage::BULK;
    std::vector<CheckpointReason> reasons;
    for (int sec = 0; sec < 1200; ++sec) {
      if (sec == 400) t.stage = ChargeStage::ABSORPTION;
      t.field_enable = sec < 1000;
      t.ibv_v = 13.0 + sec * 0.001;
      l.ChargedEnergy_AllTime_Wh = sec;
      const int before = svc.checkpoints();
      svc.onTelemetry(t, l, (100 + sec) * S, kT0 + sec * 1000LL);
      if (svc.checkpoints() != before) reasons.push_back(svc.lastReason());
    }
    // 300 s interval, stage at 400 (restarts the interval), 700, 1000, the
    // field-off edge at 1000 -> 1005, then nothing until 1305.
    const std::vector<CheckpointReason> want{CheckpointReason::Interval, CheckpointReason::Stage,
                                             CheckpointReason::Interval, CheckpointReason::Interval,
                                             CheckpointReason::FieldOff};
    EXPECT_EQ(reasons, want);
    Event e;
    e.t = 1290 * S;
    e.code = EventCode::FieldOff;
    svc.onEvents(std::span<const Event>(&e, 1), kT0 + 1200 * 1000LL, 1300 * S);
    l.ChargedEnergy_AllTime_Wh = 4242.0;
    EXPECT_TRUE(svc.stop(l, kT0 + 1200 * 1000LL).ok);
    const auto ev = svc.store().queryEvents(5);
    (void)ev;  // closed store: answers empty, must not crash
  }
  StoreService svc(st, {}, rep.fn());
  const StoreStart s1 = svc.start(kT0 + 2000 * 1000LL);
  ASSERT_TRUE(s1.restored.has_value());
  EXPECT_DOUBLE_EQ(s1.restored->ledger.ChargedEnergy_AllTime_Wh, 4242.0);
  EXPECT_EQ(s1.restored->reason, "stop");
  EXPECT_NE(s1.message.find("restored ledger saved"), std::string::npos);
  EXPECT_NE(s1.message.find(formatUtc(kT0 + 1200 * 1000LL)), std::string::npos);
  const auto ev = svc.store().queryEvents(5);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].code, "FieldOff");
  EXPECT_EQ(ev[0].tMs, kT0 + 1190 * 1000LL);  // mapped from the monotonic stamp
  EXPECT_EQ(svc.store().queryHistory("ibv_v", kT0, kT0 + 1200 * 1000LL, 0).size(), 1200u);
  EXPECT_EQ(rep.items.size(), 2u);  // the two start messages, no errors
}

TEST(StoreService, FailureStreakReportedOnceThenRecovery) {
  TempDir d;
  StoreSettings st;
  st.path = d.file("x.db");
  StoreOptions opt;
  opt.maxPageCount = 30;
  Reports rep;
  StoreService svc(st, opt, rep.fn());
  svc.start(kT0);
  std::vector<Event> evs(16);
  for (int i = 0; i < 200; ++i) svc.onEvents(evs, kT0 + i);
  int errors = 0;
  for (const auto& [lvl, msg] : rep.items)
    if (lvl == EventLevel::Error) {
      ++errors;
      EXPECT_NE(msg.find("disk full"), std::string::npos) << msg;
    }
  EXPECT_EQ(errors, 1);
  // Space again: one "work again" report.
  sql::Db db;
  ASSERT_EQ(db.open(st.path), 0);
  ASSERT_EQ(db.exec("DELETE FROM events"), 0);
  db.close();
  svc.onEvents(std::span<const Event>(evs.data(), 1), kT0 + 500);
  EXPECT_EQ(rep.items.back().first, EventLevel::Info);
  EXPECT_NE(rep.items.back().second.find("work again"), std::string::npos);
}

}  // namespace
}  // namespace xr
