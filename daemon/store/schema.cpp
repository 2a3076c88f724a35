#include "store/schema.h"

#include <sqlite3.h>

#include <string>

#include "core/trend_rows.h"

namespace xr::store {

namespace {

int setVersion(sql::Db& db, int v) { return db.exec("PRAGMA user_version = " + std::to_string(v)); }

constexpr const char* kV1 = R"sql(
CREATE TABLE IF NOT EXISTS ledger(name TEXT PRIMARY KEY, value REAL NOT NULL);
CREATE TABLE IF NOT EXISTS overrides(name TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS events(id INTEGER PRIMARY KEY, t_ms INTEGER NOT NULL, level TEXT NOT NULL,
                                  code TEXT NOT NULL, message TEXT NOT NULL);
)sql";

// v1 -> v2: the time the ledger was saved (unknown for v1 data: 0), overrides
// remember the file value they replaced, events carry reason and values.
constexpr const char* kV2 = R"sql(
CREATE TABLE ledger_meta(id INTEGER PRIMARY KEY CHECK (id = 1), saved_at_ms INTEGER NOT NULL,
                         reason TEXT NOT NULL);
INSERT INTO ledger_meta(id, saved_at_ms, reason)
  SELECT 1, 0, 'migrated from v1' WHERE EXISTS (SELECT 1 FROM ledger);
ALTER TABLE overrides ADD COLUMN file_value TEXT;
ALTER TABLE overrides ADD COLUMN changed_at_ms INTEGER NOT NULL DEFAULT 0;
ALTER TABLE events ADD COLUMN reason TEXT NOT NULL DEFAULT 'NONE';
ALTER TABLE events ADD COLUMN a REAL NOT NULL DEFAULT 0;
ALTER TABLE events ADD COLUMN b REAL NOT NULL DEFAULT 0;
CREATE TABLE kv(key TEXT PRIMARY KEY, value TEXT NOT NULL);
)sql";

// v2 -> v3: chart history. One row per (bucket start, series) holding packed
// float32 samples; the rowid is bucket * 64 + series so rows are appended at
// the end of a rowid b-tree (SQLite's cheap append path: a full leaf is not
// rebalanced with its siblings, which halves the pages written per flush).
constexpr const char* kV3 = R"sql(
CREATE TABLE series(id INTEGER PRIMARY KEY, name TEXT NOT NULL UNIQUE);
CREATE TABLE history_1s(key INTEGER PRIMARY KEY, data BLOB NOT NULL);
CREATE TABLE history_1m(key INTEGER PRIMARY KEY, data BLOB NOT NULL);
CREATE INDEX events_t ON events(t_ms);
)sql";

// v3 -> v4: "not set up" became a state (docs/configuration.md "Not set
// up"). An install that already ran (a saved ledger or a dashboard setting)
// charged with its file's values as chosen; it keeps doing so after the
// upgrade rather than drop to the not-set-up limits because the new packaged
// file no longer names a battery type.
// Also the History page's summaries (store/charge_tally.h): one row per
// local day, one per charge. NULL: not known (no reading that day).
constexpr const char* kV4 = R"sql(
INSERT INTO kv(key, value) SELECT 'set_up_before_upgrade', '1'
  WHERE EXISTS (SELECT 1 FROM ledger_meta) OR EXISTS (SELECT 1 FROM overrides);
CREATE TABLE history_days(day TEXT PRIMARY KEY, alt_ah REAL NOT NULL, alt_wh REAL NOT NULL,
  batt_ah_in REAL NOT NULL, batt_ah_out REAL NOT NULL, bulk_s REAL NOT NULL, absorption_s REAL NOT NULL,
  float_s REAL NOT NULL, idle_s REAL NOT NULL, field_on_s REAL NOT NULL, peak_alt_temp_c REAL,
  min_soc REAL, max_soc REAL);
CREATE TABLE history_charges(id INTEGER PRIMARY KEY, start_ms INTEGER NOT NULL, end_ms INTEGER NOT NULL,
  bulk_s REAL NOT NULL, absorption_s REAL NOT NULL, float_s REAL NOT NULL, alt_ah REAL NOT NULL,
  alt_wh REAL NOT NULL, start_soc REAL, end_soc REAL, end_reason TEXT NOT NULL, open INTEGER NOT NULL);
)sql";

// v4 -> v5: the History page's day rows gain what an owner reads at a
// glance (energy into the bank, the battery's lowest and highest voltage,
// the SoC at the start and end of the day, engine hours; NULL in the rows
// written before: not known), and the trends over a season: one row per
// hour and one per local day of min/mean/max (core/trend_rows.h).
constexpr const char* kV5 = R"sql(
ALTER TABLE history_days ADD COLUMN batt_wh_in REAL;
ALTER TABLE history_days ADD COLUMN v_min REAL;
ALTER TABLE history_days ADD COLUMN v_max REAL;
ALTER TABLE history_days ADD COLUMN soc_start REAL;
ALTER TABLE history_days ADD COLUMN soc_end REAL;
ALTER TABLE history_days ADD COLUMN engine_s REAL;
CREATE TABLE trends_hourly(t_s INTEGER PRIMARY KEY, day_s INTEGER NOT NULL, samples INTEGER NOT NULL,
  TREND_COLUMNS);
CREATE INDEX trends_hourly_day ON trends_hourly(day_s);
CREATE TABLE trends_daily(t_s INTEGER PRIMARY KEY, day_s INTEGER NOT NULL, samples INTEGER NOT NULL,
  TREND_COLUMNS);
)sql";

// v5 -> v6: the 1 s chart in a ring rewritten in place (kRingMinutes): the
// hourly DELETE of the rows 48 h old wrote every page it emptied into the WAL
// (a page freed in WAL mode is still written), and each flush's new pages
// touched the freelist and the file's header page (docs/performance.md
// "Storage writes"). The later of two minutes that share a slot wins.
// history_1s is emptied, not dropped: a release before this one still finds
// the tables it reads (missingForReading) and runs on the newer file.
constexpr const char* kV6 = R"sql(
CREATE TABLE history_1s_ring(slot INTEGER PRIMARY KEY, t_s INTEGER NOT NULL, data BLOB NOT NULL);
INSERT OR REPLACE INTO history_1s_ring(slot, t_s, data)
  SELECT ((key / 64 / 60) % RING_MINUTES) * 64 + key % 64, key / 64, data FROM history_1s WHERE key >= 0
  ORDER BY key;
DELETE FROM history_1s;
)sql";

std::string withRingMinutes(std::string sqlText) {
  const auto at = sqlText.find("RING_MINUTES");
  return sqlText.replace(at, 12, std::to_string(kRingMinutes));
}

// The min/mean/max columns of every trended value (core/trend_rows.h).
std::string withTrendColumns(std::string sqlText) {
  std::string cols;
  for (const auto& t : kTrendSeries)
    for (const char* k : {"_min", "_mean", "_max"})
      cols += (cols.empty() ? "" : ", ") + std::string(t.name) + k + " REAL";
  for (auto at = sqlText.find("TREND_COLUMNS"); at != std::string::npos; at = sqlText.find("TREND_COLUMNS"))
    sqlText.replace(at, 13, cols);
  return sqlText;
}

}  // namespace

int createV1(sql::Db& db) {
  int rc = db.exec(kV1);
  if (rc == SQLITE_OK) rc = setVersion(db, 1);
  return rc;
}

int migrateStep(sql::Db& db, int from) {
  switch (from) {
    case 0:
      return createV1(db);
    case 1: {
      int rc = db.exec(kV2);
      return rc == SQLITE_OK ? setVersion(db, 2) : rc;
    }
    case 2: {
      int rc = db.exec(kV3);
      return rc == SQLITE_OK ? setVersion(db, 3) : rc;
    }
    case 3: {
      int rc = db.exec(kV4);
      return rc == SQLITE_OK ? setVersion(db, 4) : rc;
    }
    case 4: {
      int rc = db.exec(withTrendColumns(kV5));
      return rc == SQLITE_OK ? setVersion(db, 5) : rc;
    }
    case 5: {
      int rc = db.exec(withRingMinutes(kV6));
      return rc == SQLITE_OK ? setVersion(db, 6) : rc;
    }
    default:
      return db.setError(SQLITE_MISMATCH, "no migration from version " + std::to_string(from));
  }
}

int migrate(sql::Db& db) {
  int rc = SQLITE_OK;
  int v = static_cast<int>(db.queryInt("PRAGMA user_version", &rc));
  if (!sql::isOk(rc)) return rc;
  if (v > kSchemaVersion)
    return db.setError(SQLITE_MISMATCH, "database schema v" + std::to_string(v) + " is newer than v" +
                                            std::to_string(kSchemaVersion));
  while (v < kSchemaVersion) {
    sql::Transaction tx(db);
    if (tx.beginRc() != SQLITE_OK) return tx.beginRc();
    rc = migrateStep(db, v);
    if (rc != SQLITE_OK) return rc;
    rc = tx.commit();
    if (rc != SQLITE_OK) return rc;
    ++v;
  }
  return SQLITE_OK;
}

std::string missingForReading(sql::Db& db) {
  // The columns the store's queries read (store_*.cpp), table by table.
  static constexpr const char* kReads[] = {
      "SELECT name, value FROM ledger",
      "SELECT saved_at_ms, reason FROM ledger_meta",
      "SELECT name, value, file_value, changed_at_ms FROM overrides",
      "SELECT id, t_ms, level, code, reason, message, a, b FROM events",
      "SELECT key, value FROM kv",
      "SELECT id, name FROM series",
      "SELECT slot, t_s, data FROM history_1s_ring",
      "SELECT key, data FROM history_1m",
      "SELECT day, alt_ah, alt_wh, batt_ah_in, batt_ah_out, bulk_s, absorption_s, float_s, idle_s, "
      "field_on_s, "
      "peak_alt_temp_c, min_soc, max_soc, batt_wh_in, v_min, v_max, soc_start, soc_end, engine_s FROM "
      "history_days",
      "SELECT t_s, day_s, samples, battery_v_min, soc_pct_max FROM trends_hourly",
      "SELECT t_s, day_s, samples, battery_v_min, soc_pct_max FROM trends_daily",
      "SELECT id, start_ms, end_ms, bulk_s, absorption_s, float_s, alt_ah, alt_wh, start_soc, end_soc, "
      "end_reason, open FROM history_charges",
  };
  for (const char* q : kReads) {
    sql::Stmt st(db, std::string(q) + " LIMIT 0");
    if (!st.ok()) return std::string(q) + ": " + db.lastError();
  }
  return {};
}

int createAtVersion(sql::Db& db, int v) {
  for (int cur = 0; cur < v; ++cur) {
    const int rc = migrateStep(db, cur);
    if (rc != SQLITE_OK) return rc;
  }
  return SQLITE_OK;
}

}  // namespace xr::store
