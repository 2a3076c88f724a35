#pragma once
// Database schema, versioned in PRAGMA user_version. Every historical version
// stays in the code as a forward migration step, so a database written by any
// earlier release is brought up to date on open (and each path is tested).
//
//   v1  ledger(name, value), overrides(name, value), events(t_ms, level, code, message)
//   v2  ledger_meta (saved time + reason), overrides gain file_value/changed_at_ms,
//       events gain reason/a/b, kv (web token, tuning logs)
//   v3  history_1s / history_1m (packed float buckets, rowid = bucket * 64 + series)
//       + series names, events index
//   v4  kv 'set_up_before_upgrade' for an install that had already run (it keeps
//       its file's values rather than the not-set-up limits); history_days and
//       history_charges (the History page's summaries)
//   v5  history_days gain batt_wh_in, v_min, v_max, soc_start, soc_end, engine_s;
//       trends_hourly / trends_daily (min/mean/max per hour and per local day)
//   v6  history_1s_ring: the 1 s chart as a ring of kRingMinutes minutes, each
//       row rewritten in place as its slot comes round (no trim); the rows of
//       history_1s move into it and that table is left empty (an older
//       release still finds it)
#include <cstdint>
#include <string>

#include "store/sqlite_db.h"

namespace xr::store {

inline constexpr int kSchemaVersion = 6;
// History rows: rowid = bucket start (s) * kSeriesSlots + series id.
inline constexpr int kSeriesSlots = 64;
// The 1 s chart's ring (v6): slot = (minute index mod kRingMinutes) *
// kSeriesSlots + series id. 48 h and an hour to spare, so the oldest minute a
// chart may ask for is never the one being rewritten.
inline constexpr std::int64_t kRingMinutes = 48 * 60 + 60;

// Creates the v1 schema on an empty database (user_version 0 -> 1).
int createV1(sql::Db& db);
// Applies the migration from version `from` to `from + 1` (from >= 1).
int migrateStep(sql::Db& db, int from);
// Brings any version 0..kSchemaVersion up to kSchemaVersion, each step in its
// own transaction. Returns SQLITE_OK, or an error (the version is then left at
// the last completed step). A version newer than ours is SQLITE_MISMATCH.
int migrate(sql::Db& db);
// Builds exactly version `v` (tests: a database "written by an older release").
int createAtVersion(sql::Db& db, int v);
// Whether every table and column this release reads exists in db (a newer
// release's database: read what we can). Empty when all
// do, else the first that does not.
std::string missingForReading(sql::Db& db);

}  // namespace xr::store
