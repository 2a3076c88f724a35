// Store: closing, configuring the connection, backups and diagnostics.
// Opening (with recovery from a damaged, newer or unwritable file) is in
// store_open.cpp; the other jobs of the class live beside it:
// store_ledger.cpp, store_settings.cpp, store_events.cpp, store_history.cpp.
#include "store/store.h"

#include <sqlite3.h>
#include <sys/stat.h>

#include "store/backup.h"
#include "store/schema.h"

namespace xr {

namespace {

// The backup holds the web token like the database: the owner may read and
// write it, its group read it when it may read the database, nobody else.
unsigned backupMode(const std::string& dbPath) {
  struct stat st {};
  if (::stat(dbPath.c_str(), &st) != 0) return 0600;
  return (static_cast<unsigned>(st.st_mode) & 0040u) | 0600u;
}

// What the daily copy leaves out: the chart history (48 h of 1 s points, a
// year of minutes) and the hourly trend rows are most of the file and are
// made again by running; copying them daily would cost the SD card more
// than everything else the daemon writes (docs/performance.md "Storage
// writes"). Settings, the ledger, the token, events, the History page's
// days and charges and the daily trend rows are all in it.
const std::string kNotBackedUp[] = {"history_1s", "history_1s_ring", "history_1m", "trends_hourly"};

}  // namespace

Store::Store(StoreOptions options) : opt_(std::move(options)), eventQueue_(opt_.eventQueue) {}

Store::~Store() { close(); }

void Store::close() {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (db_.isOpen()) {
    flushEvents(eventNowMs_, true);
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

int Store::configureConnection() {
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
  return SQLITE_OK;
}

int Store::configure() {
  int rc = configureConnection();
  if (rc != SQLITE_OK) return rc;
  if (!inMemory_) {
    // Before a migration, a verified copy of the old schema: a downgrade to
    // the release that wrote it finds its data there (docs/security.md).
    const int v = static_cast<int>(db_.queryInt("PRAGMA user_version", &rc));
    if (!sql::isOk(rc)) return rc;
    if (v >= 1 && v < store::kSchemaVersion) {
      const std::string why =
          store::writeVerifiedBackup(db_, path_ + ".bak-v" + std::to_string(v), backupMode(path_));
      // No migration without the copy: the in-memory fallback then reads
      // the old file without changing it.
      if (!why.empty()) return db_.setError(SQLITE_IOERR, "no migration without a backup (" + why + ")");
    }
  }
  return store::migrate(db_);
}

// ---------------------------------------------------------------- backups

StoreStatus Store::backup(std::int64_t nowUnixMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  StoreStatus s;
  if (!db_.isOpen() || inMemory_ || !backupsAllowed_) {
    s.ok = false;
    s.code = SQLITE_MISUSE;
    s.error = !db_.isOpen() ? "no database open"
              : inMemory_   ? "running in memory: nothing to back up"
                            : "the backup " + backupPath() + " is kept as it is (see the start-up message)";
    return s;
  }
  flushEvents(nowUnixMs, false);  // the copy holds the events up to now
  const std::string why = store::writeVerifiedBackup(db_, backupPath(), backupMode(path_), kNotBackedUp);
  if (!why.empty()) {
    s.ok = false;
    s.code = SQLITE_IOERR;
    s.error = "backup " + backupPath() + ": " + why;
    return s;
  }
  lastBackupMs_ = nowUnixMs;
  settingsChanged_ = false;
  return s;
}

StoreStatus Store::backupIfDue(std::int64_t nowUnixMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  const std::int64_t since = nowUnixMs - lastBackupMs_;
  // A wall clock set back (a GPS fix after a boot on a stale time) would make
  // `since` negative for as long as it jumped: a copy now restarts the count
  // (docs/security.md "The clock").
  const bool due = since < 0 || since >= opt_.backupIntervalS * 1000 ||
                   (settingsChanged_ && since >= opt_.settingsBackupS * 1000);
  // The retry waits an hour, unless the clock went back by more than that.
  const bool waiting = nowUnixMs < retryBackupAtMs_ && retryBackupAtMs_ - nowUnixMs <= 3'600'000;
  if (!backupsAllowed_ || inMemory_ || !db_.isOpen() || !due || waiting) return {};
  StoreStatus s = backup(nowUnixMs);
  // A failed backup (a full disk) is tried again an hour later, not every second.
  if (!s) retryBackupAtMs_ = nowUnixMs + 3'600'000;
  return s;
}

// ---------------------------------------------------------------- diagnostics

std::string Store::integrityCheck() {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  int rc = 0;
  std::string r = db_.queryText("PRAGMA integrity_check", &rc);
  return sql::isOk(rc) ? r : "error: " + db_.lastError();
}

}  // namespace xr
