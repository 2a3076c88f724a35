#include "store/store.h"

#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <random>
#include <system_error>

#include "core/modes.h"
#include "store/schema.h"

namespace xr {

namespace fs = std::filesystem;

namespace {

constexpr int kSlots = 60;  // samples per bucket: 60 s per 1 s-row, 60 min per 1 min-row

std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

std::string utcStamp(std::int64_t unixMs) {
  const std::time_t t = static_cast<std::time_t>(floorDiv(unixMs, 1000));
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%dT%H%M%SZ", &tm);
  return buf;
}

// Result codes meaning "this file is not a usable database": move it aside.
bool isCorruption(int rc) {
  const int primary = rc & 0xff;
  return primary == SQLITE_CORRUPT || primary == SQLITE_NOTADB || primary == SQLITE_MISMATCH ||
         primary == SQLITE_FORMAT;
}

// SQLite stores NaN as NULL, which the NOT NULL value columns refuse: a
// stale reading in an event's values (or a NaN ledger field) must not cost
// the whole write.
double finiteOr0(double v) { return std::isfinite(v) ? v : 0.0; }

}  // namespace

std::vector<std::string> defaultHistorySeries() {
  return {"ibv_v", "bcur_a", "alt_a", "soc_pct", "temp_f", "duty_pct", "rpm", "target_v"};
}

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

Store::Store(StoreOptions options) : opt_(std::move(options)) {}

Store::~Store() { close(); }

void Store::close() {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (db_.isOpen()) {
    closeMinute();
    flushHistory();
    db_.exec("PRAGMA wal_checkpoint(TRUNCATE)");
  }
  db_.close();
  seriesIds_.clear();
}

StoreStatus Store::status(int rc, std::string_view what) {
  StoreStatus s;
  s.ok = sql::isOk(rc);
  s.code = rc;
  if (!s.ok) {
    s.diskFull = (rc & 0xff) == SQLITE_FULL;
    s.error = std::string(what) + ": " + db_.lastError();
  }
  return s;
}

int Store::configure() {
  int rc = db_.exec("PRAGMA busy_timeout = " + std::to_string(opt_.busyTimeoutMs));
  if (rc != SQLITE_OK) return rc;
  if (!inMemory_) {
    const std::string mode = db_.queryText("PRAGMA journal_mode = WAL", &rc);
    if (!sql::isOk(rc)) return rc;
    if (mode != "wal") return db_.setError(SQLITE_CANTOPEN, "journal_mode WAL refused (" + mode + ")");
  }
  // NORMAL: in WAL mode a crash never corrupts, a power cut may lose the last
  // commits; checkpoint() switches to FULL for the ledger.
  rc = db_.exec("PRAGMA synchronous = NORMAL");
  if (rc != SQLITE_OK) return rc;
  // Debian builds SQLite with secure_delete on: every freed page (history
  // retention) would be zeroed on disk. FAST zeroes only when it costs no
  // extra I/O. The WAL file is kept to 4 MiB after each checkpoint.
  db_.queryText("PRAGMA secure_delete = FAST", &rc);
  if (!sql::isOk(rc)) return rc;
  db_.queryInt("PRAGMA journal_size_limit = 4194304", &rc);
  if (!sql::isOk(rc)) return rc;
  if (opt_.maxPageCount > 0) {
    db_.queryInt("PRAGMA max_page_count = " + std::to_string(opt_.maxPageCount), &rc);
    if (!sql::isOk(rc)) return rc;
  }
  // Reading the file proves it is a database (NOTADB shows up here).
  const std::string check = db_.queryText("PRAGMA quick_check", &rc);
  if (!sql::isOk(rc)) return rc;
  if (check != "ok") return db_.setError(SQLITE_CORRUPT, "quick_check: " + check);
  return store::migrate(db_);
}

OpenResult Store::open(const std::string& path, std::int64_t nowUnixMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  close();
  OpenResult r;
  path_ = path;
  inMemory_ = false;
  std::error_code ec;
  const fs::path p(path);
  if (p.has_parent_path()) fs::create_directories(p.parent_path(), ec);

  int rc = SQLITE_CANTOPEN;
  const bool existed = fs::exists(p, ec);
  if (existed) {
    // Version before migration, for the log (0 when unreadable).
    rc = db_.open(path);
    if (rc == SQLITE_OK) {
      int vrc = 0;
      r.fromVersion = static_cast<int>(db_.queryInt("PRAGMA user_version", &vrc));
      if (!sql::isOk(vrc)) r.fromVersion = 0;
      rc = configure();
    }
  } else {
    rc = db_.open(path);
    if (rc == SQLITE_OK) rc = configure();
  }

  if (rc != SQLITE_OK && existed && isCorruption(rc)) {
    // A corrupt or foreign file never stops charging: keep a copy, start fresh.
    const std::string why = db_.lastError();
    db_.close();
    const std::string copy = path + ".corrupt-" + utcStamp(nowUnixMs);
    fs::rename(p, copy, ec);
    if (!ec) {
      for (const char* suffix : {"-wal", "-shm"}) {
        std::error_code e2;
        if (fs::exists(path + suffix, e2)) fs::rename(path + suffix, copy + suffix, e2);
      }
      r.recovered = true;
      r.corruptCopy = copy;
      r.message = "database " + path + " unreadable (" + why + "); kept as " + copy + ", started fresh";
      rc = db_.open(path);
      if (rc == SQLITE_OK) rc = configure();
    } else {
      r.message = "database " + path + " unreadable (" + why + ") and could not be moved aside (" +
                  ec.message() + ")";
    }
  }

  if (rc == SQLITE_OK) {
    r.ok = true;
    if (r.message.empty())
      r.message = existed ? "database " + path + " opened (schema v" + std::to_string(r.fromVersion) +
                                " -> v" + std::to_string(store::kSchemaVersion) + ")"
                          : "database " + path + " created";
  } else {
    // Last resort: an in-memory database keeps the API working (overrides,
    // events, charts for this session); nothing survives a restart.
    const std::string why = db_.lastError();
    db_.close();
    inMemory_ = true;
    r.inMemory = true;
    r.ok = false;
    r.message += (r.message.empty() ? "" : "; ") + std::string("cannot use database ") + path + " (" + why +
                 "): running without persistence";
    rc = db_.open(":memory:");
    // A read-only state directory (read-only root file systems exist) still
    // lets us read the last checkpoint: copy the file into memory.
    if (rc == SQLITE_OK && existed && !r.recovered && path.find_first_of("?#%") == std::string::npos) {
      sql::Db ro;
      if (ro.open("file:" + path + "?immutable=1", SQLITE_OPEN_READONLY | SQLITE_OPEN_URI) == SQLITE_OK) {
        if (sqlite3_backup* b = sqlite3_backup_init(db_.handle(), "main", ro.handle(), "main")) {
          const int brc = sqlite3_backup_step(b, -1);
          sqlite3_backup_finish(b);
          if (brc == SQLITE_DONE) r.message += "; last saved state loaded read-only";
        }
      }
    }
    if (rc == SQLITE_OK) rc = configure();
    if (rc != SQLITE_OK) {
      // The copy was unusable: an empty in-memory database then.
      db_.close();
      rc = db_.open(":memory:");
      if (rc == SQLITE_OK) rc = configure();
      if (rc != SQLITE_OK) db_.close();
    }
  }
  seriesIds_.clear();
  if (db_.isOpen())
    for (const auto& s : opt_.historySeries) seriesIds_.push_back(seriesId(s));
  return r;
}

// ---------------------------------------------------------------- ledger

StoreStatus Store::checkpoint(const BatteryLedger& ledger, std::string_view reason, std::int64_t nowUnixMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (!db_.isOpen()) return status(SQLITE_MISUSE, "checkpoint");
  db_.exec("PRAGMA synchronous = FULL");
  int rc;
  {
    sql::Transaction tx(db_);
    rc = tx.beginRc();
    if (rc == SQLITE_OK) {
      sql::Stmt st(db_,
                   "INSERT INTO ledger(name, value) VALUES(?1, ?2) "
                   "ON CONFLICT(name) DO UPDATE SET value = excluded.value");
      BatteryLedger copy = ledger;
      visitLedgerFields(copy, [&](const char* name, double& v) {
        if (rc != SQLITE_OK || !std::isfinite(v)) return;  // NaN: keep the last good value
        st.reset();
        const int s = st.bind(1, std::string_view(name)).bind(2, v).step();
        if (s != SQLITE_DONE) rc = s;
      });
    }
    if (rc == SQLITE_OK) {
      sql::Stmt meta(
          db_,
          "INSERT INTO ledger_meta(id, saved_at_ms, reason) VALUES(1, ?1, ?2) "
          "ON CONFLICT(id) DO UPDATE SET saved_at_ms = excluded.saved_at_ms, reason = excluded.reason");
      const int s = meta.bind(1, nowUnixMs).bind(2, reason).step();
      if (s != SQLITE_DONE) rc = s;
    }
    if (rc == SQLITE_OK) rc = tx.commit();
  }
  db_.exec("PRAGMA synchronous = NORMAL");
  return status(rc, "checkpoint");
}

std::optional<SavedLedger> Store::loadLedger() {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (!db_.isOpen()) return std::nullopt;
  SavedLedger out;
  std::map<std::string, double, std::less<>> values;
  {
    sql::Stmt st(db_, "SELECT name, value FROM ledger");
    if (!st.ok()) return std::nullopt;
    while (st.step() == SQLITE_ROW) values[st.colText(0)] = st.colDouble(1);
  }
  if (values.empty()) return std::nullopt;
  visitLedgerFields(out.ledger, [&](const char* name, double& v) {
    const auto it = values.find(std::string_view(name));
    if (it != values.end()) v = it->second;  // fields added later keep their defaults
  });
  out.ledger.valid = true;
  sql::Stmt meta(db_, "SELECT saved_at_ms, reason FROM ledger_meta WHERE id = 1");
  if (meta.ok() && meta.step() == SQLITE_ROW) {
    out.savedAtMs = meta.colInt(0);
    out.reason = meta.colText(1);
  }
  return out;
}

StoreStatus Store::putBlob(std::string_view key, std::string_view value) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(
      db_, "INSERT INTO kv(key, value) VALUES(?1, ?2) ON CONFLICT(key) DO UPDATE SET value = excluded.value");
  return status(st.bind(1, key).bind(2, value).step(), "putBlob");
}

std::optional<std::string> Store::getBlob(std::string_view key) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(db_, "SELECT value FROM kv WHERE key = ?1");
  if (st.bind(1, key).step() == SQLITE_ROW) return st.colText(0);
  return std::nullopt;
}

// ---------------------------------------------------------------- overrides

StoreStatus Store::setOverride(std::string_view name, std::string_view value, std::string_view fileValue,
                               std::int64_t nowUnixMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(db_,
               "INSERT INTO overrides(name, value, file_value, changed_at_ms) VALUES(?1, ?2, ?3, ?4) "
               "ON CONFLICT(name) DO UPDATE SET value = excluded.value, file_value = excluded.file_value, "
               "changed_at_ms = excluded.changed_at_ms");
  return status(st.bind(1, name).bind(2, value).bind(3, fileValue).bind(4, nowUnixMs).step(), "setOverride");
}

std::vector<OverrideRow> Store::overrides() {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  std::vector<OverrideRow> out;
  sql::Stmt st(db_, "SELECT name, value, file_value, changed_at_ms FROM overrides ORDER BY name");
  while (st.ok() && st.step() == SQLITE_ROW)
    out.push_back(OverrideRow{st.colText(0), st.colText(1), st.colText(2), st.colInt(3)});
  return out;
}

std::optional<OverrideRow> Store::findOverride(std::string_view name) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(db_, "SELECT name, value, file_value, changed_at_ms FROM overrides WHERE name = ?1");
  if (st.bind(1, name).step() == SQLITE_ROW)
    return OverrideRow{st.colText(0), st.colText(1), st.colText(2), st.colInt(3)};
  return std::nullopt;
}

StoreStatus Store::resetOverride(std::string_view name) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(db_, "DELETE FROM overrides WHERE name = ?1");
  return status(st.bind(1, name).step(), "resetOverride");
}

// ---------------------------------------------------------------- events

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
  sql::Stmt st(db_,
               "SELECT id, t_ms, level, code, reason, message, a, b FROM events WHERE t_ms < ?1 "
               "ORDER BY t_ms DESC, id DESC LIMIT ?2");
  st.bind(1, beforeMs.value_or(INT64_MAX)).bind(2, static_cast<std::int64_t>(limit));
  return readEvents(st);
}

std::vector<EventRecord> Store::queryEventsBeforeId(std::size_t limit, std::int64_t beforeId) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(db_,
               "SELECT id, t_ms, level, code, reason, message, a, b FROM events WHERE id < ?1 "
               "ORDER BY id DESC LIMIT ?2");
  st.bind(1, beforeId).bind(2, static_cast<std::int64_t>(limit));
  return readEvents(st);
}

// ---------------------------------------------------------------- history

int Store::seriesId(std::string_view name) {
  sql::Stmt ins(db_, "INSERT OR IGNORE INTO series(name) VALUES(?1)");
  ins.bind(1, name).step();
  sql::Stmt sel(db_, "SELECT id FROM series WHERE name = ?1");
  if (sel.bind(1, name).step() == SQLITE_ROW) {
    const auto id = sel.colInt(0);
    if (id >= 0 && id < store::kSeriesSlots) return static_cast<int>(id);
  }
  return -1;
}

void Store::closeMinute() {
  if (aggMinute_ < 0) return;
  const std::size_t n = opt_.historySeries.size();
  const std::int64_t hour = floorDiv(aggMinute_, 60) * 60;  // minute index -> hour bucket (in minutes)
  Bucket& b = pending1m_[hour * 60];
  if (b.data.empty()) b.data.assign(n * kSlots, NAN);
  const int slot = static_cast<int>(aggMinute_ - hour);
  for (std::size_t s = 0; s < n; ++s)
    if (aggCount_[s] > 0) b.data[s * kSlots + slot] = static_cast<float>(aggSum_[s] / aggCount_[s]);
  aggMinute_ = -1;
}

StoreStatus Store::appendHistory(std::int64_t tUnixMs, std::span<const double> values) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  const std::size_t n = opt_.historySeries.size();
  if (values.size() != n) return status(SQLITE_MISUSE, "appendHistory: wrong number of series");
  const std::int64_t sec = floorDiv(tUnixMs, 1000);
  const std::int64_t minute = floorDiv(sec, 60);
  Bucket& b = pending1s_[minute * 60];
  if (b.data.empty()) b.data.assign(n * kSlots, NAN);
  const int slot = static_cast<int>(sec - minute * 60);
  for (std::size_t s = 0; s < n; ++s) b.data[s * kSlots + slot] = static_cast<float>(values[s]);

  // Downsample on insert: the 1 min table gets each finished minute's mean.
  if (minute != aggMinute_) {
    closeMinute();
    aggMinute_ = minute;
    aggSum_.assign(n, 0.0);
    aggCount_.assign(n, 0);
  }
  for (std::size_t s = 0; s < n; ++s)
    if (std::isfinite(values[s])) {
      aggSum_[s] += values[s];
      ++aggCount_[s];
    }

  if (lastFlushS_ < 0) lastFlushS_ = sec;
  if (sec - lastFlushS_ >= opt_.historyFlushS) {
    lastFlushS_ = sec;
    StoreStatus st = flushPending(false);
    if (st && sec - lastCompactS_ >= 3600) {
      lastCompactS_ = sec;
      st = compact(tUnixMs);
    }
    return st;
  }
  return {};
}

int Store::writeBuckets(std::string_view table, std::map<std::int64_t, Bucket>& pending, std::int64_t) {
  const std::size_t n = opt_.historySeries.size();
  sql::Stmt sel(db_, "SELECT data FROM " + std::string(table) + " WHERE key = ?1");
  sql::Stmt ins(db_, "INSERT OR REPLACE INTO " + std::string(table) + "(key, data) VALUES(?1, ?2)");
  if (!sel.ok()) return sel.prepareRc();
  if (!ins.ok()) return ins.prepareRc();
  std::vector<float> row(kSlots);
  for (auto& [bucket, b] : pending) {
    for (std::size_t s = 0; s < n; ++s) {
      if (s >= seriesIds_.size() || seriesIds_[s] < 0) continue;  // no id: series not recorded
      const float* src = &b.data[s * kSlots];
      if (std::none_of(src, src + kSlots, [](float v) { return !std::isnan(v); })) continue;
      std::fill(row.begin(), row.end(), NAN);
      const std::int64_t key = bucket * store::kSeriesSlots + seriesIds_[s];
      sel.reset();
      if (sel.bind(1, key).step() == SQLITE_ROW) {
        const auto blob = sel.colBlob(0);
        if (blob.size() == kSlots * sizeof(float)) std::memcpy(row.data(), blob.data(), blob.size());
      }
      for (int i = 0; i < kSlots; ++i)
        if (!std::isnan(src[i])) row[i] = src[i];
      ins.reset();
      const auto* bytes = reinterpret_cast<const std::uint8_t*>(row.data());
      const int rc =
          ins.bind(1, key).bindBlob(2, std::span<const std::uint8_t>(bytes, kSlots * sizeof(float))).step();
      if (rc != SQLITE_DONE) return rc;
    }
  }
  return SQLITE_OK;
}

StoreStatus Store::flushHistory() {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  return flushPending(true);
}

StoreStatus Store::flushPending(bool all) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  // The periodic flush writes a 1 min row only once its hour is complete:
  // rewriting the open hour's rows every flush would cost pages for data the
  // 1 s table already holds. flushHistory()/close() write everything.
  std::map<std::int64_t, Bucket> keep1m;
  if (!all && aggMinute_ >= 0) {
    const std::int64_t openHour = floorDiv(aggMinute_, 60) * 3600;
    for (auto it = pending1m_.lower_bound(openHour); it != pending1m_.end();) {
      keep1m.insert(std::move(*it));
      it = pending1m_.erase(it);
    }
  }
  StoreStatus st;
  if (!pending1s_.empty() || !pending1m_.empty()) {
    if (!db_.isOpen()) {
      st = status(SQLITE_MISUSE, "flushHistory");
    } else {
      sql::Transaction tx(db_);
      int rc = tx.beginRc();
      if (rc == SQLITE_OK) rc = writeBuckets("history_1s", pending1s_, 60);
      if (rc == SQLITE_OK) rc = writeBuckets("history_1m", pending1m_, 3600);
      if (rc == SQLITE_OK) rc = tx.commit();
      st = status(rc, "flushHistory");
    }
  }
  // On error the buffer is dropped anyway: bounded memory beats chart history.
  pending1s_.clear();
  pending1m_ = std::move(keep1m);
  return st;
}

StoreStatus Store::compact(std::int64_t nowUnixMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (!db_.isOpen()) return status(SQLITE_MISUSE, "compact");
  const std::int64_t nowS = floorDiv(nowUnixMs, 1000);
  sql::Transaction tx(db_);
  int rc = tx.beginRc();
  if (rc == SQLITE_OK) {
    sql::Stmt st(db_, "DELETE FROM history_1s WHERE key < ?1");
    rc = st.bind(1, (nowS - opt_.history1sKeepS - 60) * store::kSeriesSlots).step();
  }
  if (rc == SQLITE_DONE) {
    sql::Stmt st(db_, "DELETE FROM history_1m WHERE key < ?1");
    rc = st.bind(1, (nowS - opt_.history1mKeepS - 3600) * store::kSeriesSlots).step();
  }
  if (rc == SQLITE_DONE) {
    sql::Stmt st(db_, "DELETE FROM events WHERE id <= (SELECT max(id) FROM events) - ?1");
    rc = st.bind(1, opt_.maxEvents).step();
  }
  if (rc == SQLITE_DONE) rc = tx.commit();
  return status(rc, "compact");
}

std::vector<HistoryPoint> Store::queryHistory(std::string_view series, std::int64_t fromMs, std::int64_t toMs,
                                              std::int64_t stepMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  std::vector<HistoryPoint> out;
  const auto it = std::find(opt_.historySeries.begin(), opt_.historySeries.end(), series);
  if (it == opt_.historySeries.end() || toMs < fromMs || !db_.isOpen()) return out;
  const std::size_t s = static_cast<std::size_t>(it - opt_.historySeries.begin());
  if (s >= seriesIds_.size() || seriesIds_[s] < 0) return out;
  const std::int64_t newest =
      pending1s_.empty() ? toMs : std::max(toMs, (pending1s_.rbegin()->first + 60) * 1000);
  const bool fine = stepMs < 60000 && fromMs >= (newest - opt_.history1sKeepS * 1000);
  const std::int64_t slotS = fine ? 1 : 60;
  const std::int64_t spanS = slotS * kSlots;
  const std::int64_t fromS = floorDiv(fromMs, 1000), toS = floorDiv(toMs, 1000);

  std::map<std::int64_t, float> points;  // t (s) -> value
  auto take = [&](std::int64_t bucket, const float* row) {
    for (int i = 0; i < kSlots; ++i) {
      const std::int64_t t = bucket + i * slotS;
      if (t >= fromS && t <= toS && !std::isnan(row[i])) points[t] = row[i];
    }
  };
  {
    sql::Stmt st(db_, std::string("SELECT key, data FROM ") + (fine ? "history_1s" : "history_1m") +
                          " WHERE key >= ?1 AND key <= ?2 AND key % ?3 = ?4 ORDER BY key");
    st.bind(1, floorDiv(fromS, spanS) * spanS * store::kSeriesSlots)
        .bind(2, toS * store::kSeriesSlots + store::kSeriesSlots - 1)
        .bind(3, store::kSeriesSlots)
        .bind(4, seriesIds_[s]);
    std::vector<float> row(kSlots);
    while (st.ok() && st.step() == SQLITE_ROW) {
      const auto blob = st.colBlob(1);
      if (blob.size() != kSlots * sizeof(float)) continue;
      std::memcpy(row.data(), blob.data(), blob.size());
      take(floorDiv(st.colInt(0), store::kSeriesSlots), row.data());
    }
  }
  for (const auto& [bucket, b] : fine ? pending1s_ : pending1m_) take(bucket, &b.data[s * kSlots]);

  const std::int64_t stepS = std::max<std::int64_t>(slotS, stepMs / 1000);
  if (stepS <= slotS) {
    for (const auto& [t, v] : points) out.push_back({t * 1000, v});
    return out;
  }
  std::int64_t bin = INT64_MIN;
  double sum = 0.0;
  int count = 0;
  for (const auto& [t, v] : points) {
    const std::int64_t b = fromS + floorDiv(t - fromS, stepS) * stepS;
    if (b != bin && count > 0) {
      out.push_back({bin * 1000, sum / count});
      sum = 0.0;
      count = 0;
    }
    bin = b;
    sum += v;
    ++count;
  }
  if (count > 0) out.push_back({bin * 1000, sum / count});
  return out;
}

// ---------------------------------------------------------------- token

std::string Store::getOrCreateToken() {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (auto t = getBlob("web_token"); t && !t->empty()) return *t;
  std::uint8_t bytes[32];
  bool got = false;
  if (std::ifstream urandom("/dev/urandom", std::ios::binary); urandom) {
    urandom.read(reinterpret_cast<char*>(bytes), sizeof bytes);
    got = urandom.gcount() == sizeof bytes;
  }
  if (!got) {
    std::random_device rd;
    for (auto& b : bytes) b = static_cast<std::uint8_t>(rd());
  }
  static const char* hex = "0123456789abcdef";
  std::string token;
  for (std::uint8_t b : bytes) {
    token += hex[b >> 4];
    token += hex[b & 15];
  }
  putBlob("web_token", token);  // a failure just means a new token next start
  return token;
}

std::string Store::integrityCheck() {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  int rc = 0;
  std::string r = db_.queryText("PRAGMA integrity_check", &rc);
  return sql::isOk(rc) ? r : "error: " + db_.lastError();
}

}  // namespace xr
