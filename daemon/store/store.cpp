// Store: opening (with recovery from a corrupt or unwritable file), closing,
// configuring the connection, and diagnostics. The other jobs of the class
// live beside it: store_ledger.cpp, store_settings.cpp, store_events.cpp,
// store_history.cpp.
#include "store/store.h"

#include <sqlite3.h>

#include <ctime>
#include <filesystem>
#include <system_error>

#include "store/floor_div.h"
#include "store/schema.h"

namespace xr {

namespace fs = std::filesystem;

namespace {

std::string utcStamp(std::int64_t unixMs) {
  const std::time_t t = static_cast<std::time_t>(store::floorDiv(unixMs, 1000));
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
}  // namespace

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

// ---------------------------------------------------------------- diagnostics

std::string Store::integrityCheck() {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  int rc = 0;
  std::string r = db_.queryText("PRAGMA integrity_check", &rc);
  return sql::isOk(rc) ? r : "error: " + db_.lastError();
}

}  // namespace xr
