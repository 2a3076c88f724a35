// Store: the event log (append in one transaction, page newest first).
#include <sqlite3.h>

#include <cmath>
#include <cstdint>

#include "core/modes.h"
#include "store/store.h"

namespace xr {

namespace {

// SQLite stores NaN as NULL, which the NOT NULL value columns refuse: a
// stale reading in an event's values (or a NaN ledger field) must not cost
// the whole write.
double finiteOr0(double v) { return std::isfinite(v) ? v : 0.0; }

}  // namespace

EventRecord toEventRecord(const Event& e, std::int64_t tUnixMs) {
  EventRecord r;
  r.tMs = tUnixMs;
  r.level = std::string(toString(e.level));
  r.code = std::string(toString(e.code));
  r.reason = std::string(toString(e.reason));
  r.message = describe(e);
  r.a = e.a;
  r.b = e.b;
  return r;
}

StoreStatus Store::appendEvents(std::span<const EventRecord> events) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (events.empty()) return {};
  if (!db_.isOpen()) return status(SQLITE_MISUSE, "appendEvents");
  sql::Transaction tx(db_);
  int rc = tx.beginRc();
  if (rc == SQLITE_OK) {
    sql::Stmt st(db_,
                 "INSERT INTO events(t_ms, level, code, reason, message, a, b) VALUES(?1,?2,?3,?4,?5,?6,?7)");
    for (const auto& e : events) {
      st.reset();
      const int s = st.bind(1, e.tMs)
                        .bind(2, e.level)
                        .bind(3, e.code)
                        .bind(4, e.reason)
                        .bind(5, e.message)
                        .bind(6, finiteOr0(e.a))
                        .bind(7, finiteOr0(e.b))
                        .step();
      if (s != SQLITE_DONE) {
        rc = s;
        break;
      }
    }
  }
  if (rc == SQLITE_OK) rc = tx.commit();
  return status(rc, "appendEvents");
}

StoreStatus Store::queueEvent(const EventRecord& e, std::int64_t nowMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  eventNowMs_ = nowMs;
  eventQueue_.push(e);
  return eventQueue_.due(nowMs) ? flushEvents(nowMs, false) : StoreStatus{};
}

StoreStatus Store::flushEventsIfDue(std::int64_t nowMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  eventNowMs_ = nowMs;
  return eventQueue_.due(nowMs) ? flushEvents(nowMs, false) : StoreStatus{};
}

StoreStatus Store::flushEvents(std::int64_t nowMs, bool all) {
  const std::vector<EventRecord> rows = eventQueue_.take(nowMs, all);
  if (rows.empty()) return {};
  eventQueue_.written(nowMs);
  return appendEvents(rows);
}

namespace {
std::vector<EventRecord> readEvents(sql::Stmt& st) {
  std::vector<EventRecord> out;
  while (st.ok() && st.step() == SQLITE_ROW) {
    EventRecord e;
    e.id = st.colInt(0);
    e.tMs = st.colInt(1);
    e.level = st.colText(2);
    e.code = st.colText(3);
    e.reason = st.colText(4);
    e.message = st.colText(5);
    e.a = st.colDouble(6);
    e.b = st.colDouble(7);
    out.push_back(std::move(e));
  }
  return out;
}
}  // namespace

std::vector<EventRecord> Store::queryEvents(std::size_t limit, std::optional<std::int64_t> beforeMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (eventQueue_.pending() > 0) flushEvents(eventNowMs_, false);  // what was queued is shown
  sql::Stmt st(db_,
               "SELECT id, t_ms, level, code, reason, message, a, b FROM events WHERE t_ms < ?1 "
               "ORDER BY t_ms DESC, id DESC LIMIT ?2");
  st.bind(1, beforeMs.value_or(INT64_MAX)).bind(2, static_cast<std::int64_t>(limit));
  return readEvents(st);
}

std::vector<EventRecord> Store::queryEventsBeforeId(std::size_t limit, std::int64_t beforeId) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (eventQueue_.pending() > 0) flushEvents(eventNowMs_, false);
  sql::Stmt st(db_,
               "SELECT id, t_ms, level, code, reason, message, a, b FROM events WHERE id < ?1 "
               "ORDER BY id DESC LIMIT ?2");
  st.bind(1, beforeId).bind(2, static_cast<std::int64_t>(limit));
  return readEvents(st);
}

}  // namespace xr
