// Store::open: every way a state database can be found at start, and what
// becomes of the user's data in each (docs/operations.md,
// "The state database").
//
//   healthy, our schema or older  migrate (after a .bak-v<N> copy), back up, run
//   damaged or unreadable         keep aside as .corrupt-<time>, restore .bak
//   empty or missing, .bak usable restore .bak
//   newer schema (a downgrade)    never written: read into memory, save nothing
//   cannot be written at all      in memory with the last saved state loaded
#include <sqlite3.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>

#include "core/wall_time_text.h"
#include "store/backup.h"
#include "store/schema.h"
#include "store/store.h"

namespace xr {

namespace fs = std::filesystem;

namespace {

// How the owner reads a backup's age in a message.
std::string utcMinute(std::int64_t unixMs) {
  return wallTimeText(unixMs, "%Y-%m-%d %H:%M UTC", TimeZone::Utc);
}

// Result codes meaning "this file is not a usable database": move it aside.
// (A newer schema is not one of them: it is found before any of this.)
bool isCorruption(int rc) {
  const int primary = rc & 0xff;
  return primary == SQLITE_CORRUPT || primary == SQLITE_NOTADB || primary == SQLITE_FORMAT;
}

void removeDatabaseFiles(const std::string& path) {
  std::error_code ec;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(path + suffix, ec);
}

}  // namespace

// The backup beside the database, checked (integrity_check) only when a
// path needs it.
struct Store::BackupProbe {
  explicit BackupProbe(std::string p) : path(std::move(p)) {}
  const store::BackupCheck& check() {
    if (!checked) checked = store::checkBackup(path, store::kSchemaVersion);
    return *checked;
  }
  std::string restoredText() {
    return "restored from the verified backup " + path + " of " + utcMinute(check().mtimeMs) +
           " (changes after it are lost; the charts and hourly trends, not in the copy, start again)";
  }
  std::string path;
  std::optional<store::BackupCheck> checked;
};

OpenResult Store::open(const std::string& path, std::int64_t nowUnixMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  close();
  OpenResult r;
  path_ = path;
  inMemory_ = false;
  backupsAllowed_ = false;
  lastBackupMs_ = 0;
  retryBackupAtMs_ = 0;
  settingsChanged_ = false;
  std::error_code ec;
  const fs::path p(path);
  if (p.has_parent_path()) fs::create_directories(p.parent_path(), ec);

  BackupProbe bak(backupPath());
  // A backup written by a newer release is never replaced by ours.
  bool mayBackup = !fs::exists(bak.path, ec) || store::peekVersion(bak.path) <= store::kSchemaVersion;
  const bool existed = fs::exists(p, ec);
  const bool empty = existed && fs::is_regular_file(p, ec) && fs::file_size(p, ec) == 0;
  int rc = SQLITE_CANTOPEN;
  std::string damage;  // why the file on disk is not usable
  if (existed && !empty) {
    const int v = store::peekVersion(path);
    if (v > store::kSchemaVersion) {
      // A downgrade: that release's data is never migrated down, moved or
      // written; this run reads it and keeps nothing.
      openNewer(r, v);
    } else {
      r.fromVersion = std::max(v, 0);
      rc = openAndConfigure(path);
      if (rc != SQLITE_OK && isCorruption(rc)) damage = db_.lastError();
    }
  } else if (bak.check().usable) {
    // No database (or an empty file) beside a good backup: the file was lost
    // (a card fault, a stray rm), not a first start. Deleting both starts afresh.
    if (empty)
      damage = "the file is empty";
    else {
      rc = restoreFromBackup(r, bak.check().mtimeMs);
      r.message =
          "database " + path + " was missing; " +
          (rc == SQLITE_OK ? bak.restoredText() : "restoring the backup failed (" + db_.lastError() + ")");
      if (rc != SQLITE_OK) mayBackup = false;
    }
  } else {
    rc = openAndConfigure(path);
  }
  if (!damage.empty()) rc = recoverDamaged(r, damage, nowUnixMs, bak, mayBackup);
  finishOpen(r, rc, existed, mayBackup, nowUnixMs);
  return r;
}

int Store::openAndConfigure(const std::string& path) {
  int rc = db_.open(path);
  if (rc == SQLITE_OK) rc = configure();
  return rc;
}

// A damaged file never stops charging: keep it aside, bring the data back
// from the backup, else start fresh and say what was reset.
int Store::recoverDamaged(OpenResult& r, const std::string& damage, std::int64_t nowUnixMs, BackupProbe& bak,
                          bool& mayBackup) {
  db_.close();
  std::error_code ec;
  const std::string copy = path_ + ".corrupt-" + wallTimeText(nowUnixMs, "%Y%m%dT%H%M%SZ", TimeZone::Utc);
  fs::rename(path_, copy, ec);
  const std::string head = "database " + path_ + " damaged (" + damage + ")";
  if (ec) {
    db_.setError(SQLITE_CANTOPEN, head + " and could not be moved aside (" + ec.message() + ")");
    r.message = head + " and could not be moved aside (" + ec.message() + ")";
    return SQLITE_CANTOPEN;
  }
  for (const char* suffix : {"-wal", "-shm"}) {
    std::error_code e2;
    if (fs::exists(path_ + suffix, e2)) fs::rename(path_ + suffix, copy + suffix, e2);
  }
  r.recovered = true;
  r.corruptCopy = copy;
  int rc = SQLITE_CANTOPEN;
  std::string restoreWhy = bak.check().why;
  if (bak.check().usable) {
    rc = restoreFromBackup(r, bak.check().mtimeMs);
    if (rc == SQLITE_OK)
      r.message = head + ", kept as " + copy + "; " + bak.restoredText();
    else
      restoreWhy = "restoring it failed: " + db_.lastError();
    mayBackup = rc == SQLITE_OK;  // a good copy that did not restore stays as it is
  }
  if (rc != SQLITE_OK) {
    rc = openAndConfigure(path_);
    r.message = head + ", kept as " + copy + "; no usable backup (" + restoreWhy +
                "): started fresh, the dashboard settings, lifetime energy and web token are reset";
  }
  return rc;
}

// The open's outcome: the message, the first backup of the run, or the
// in-memory database when nothing on disk can be used.
void Store::finishOpen(OpenResult& r, int rc, bool existed, bool mayBackup, std::int64_t nowUnixMs) {
  if (r.newerSchema) {
    // openNewer() filled r and the in-memory database.
  } else if (rc == SQLITE_OK) {
    r.ok = true;
    if (r.message.empty())
      r.message = existed ? "database " + path_ + " opened (schema v" + std::to_string(r.fromVersion) +
                                " -> v" + std::to_string(store::kSchemaVersion) + ")"
                          : "database " + path_ + " created";
    backupsAllowed_ = mayBackup;
    if (r.restored) {
      lastBackupMs_ = r.backupTakenAtMs;  // the copy is this data: the next one is due a day after it
    } else if (backupsAllowed_) {
      if (const StoreStatus st = backup(nowUnixMs); !st) {
        r.backupError = st.error;
        r.message += "; " + st.error;
      }
    } else {
      r.message += "; the backup " + backupPath() + " is kept as it is and no new one is written this run";
    }
  } else {
    openInMemory(r, existed && !r.recovered);
  }
  seriesIds_.clear();
  if (db_.isOpen())
    for (const auto& s : opt_.historySeries) seriesIds_.push_back(seriesId(s));
}

int Store::restoreFromBackup(OpenResult& r, std::int64_t backupTakenAtMs) {
  removeDatabaseFiles(path_);  // nothing of a lost file mixes with the copy
  int rc = db_.open(path_);
  if (rc == SQLITE_OK) rc = store::copyInto(db_, backupPath(), "mode=ro");
  if (rc == SQLITE_OK) rc = configure();  // WAL again; migrates an older copy
  if (rc != SQLITE_OK) {
    db_.close();
    removeDatabaseFiles(path_);
    return rc;
  }
  r.restored = true;
  r.backupUsed = backupPath();
  r.backupTakenAtMs = backupTakenAtMs;
  return rc;
}

void Store::openNewer(OpenResult& r, int version) {
  r.newerSchema = true;
  r.inMemory = true;
  r.fromVersion = version;
  inMemory_ = true;
  const std::string head = "database " + path_ + " has schema v" + std::to_string(version) +
                           ", newer than this release's v" + std::to_string(store::kSchemaVersion) +
                           " (a downgrade?): it is left untouched and NOTHING IS SAVED this run";
  // Read what we can: the newer file itself, when the tables and columns
  // this release reads are all still there.
  std::string unreadable = "cannot be copied";
  for (const char* mode : {"mode=ro", "immutable=1"}) {
    if (db_.open(":memory:") != SQLITE_OK) break;
    if (store::copyInto(db_, path_, mode) == SQLITE_OK && configureConnection() == SQLITE_OK) {
      unreadable = store::missingForReading(db_);
      if (unreadable.empty()) {
        r.message = head + "; its settings, lifetime energy and web token are read from it";
        return;
      }
      break;
    }
    unreadable = db_.lastError();
  }
  // Else the last backup of ours, migrated in memory.
  db_.close();
  const store::BackupCheck b = store::checkBackup(backupPath(), store::kSchemaVersion);
  if (b.usable && db_.open(":memory:") == SQLITE_OK &&
      store::copyInto(db_, backupPath(), "mode=ro") == SQLITE_OK && configure() == SQLITE_OK) {
    r.backupUsed = backupPath();
    r.backupTakenAtMs = b.mtimeMs;
    r.message = head + "; this release cannot read it (" + unreadable + "), so the backup " + backupPath() +
                " of " + utcMinute(b.mtimeMs) + " is used";
    return;
  }
  db_.close();
  if (db_.open(":memory:") == SQLITE_OK && configure() != SQLITE_OK) db_.close();
  r.message = head + "; this release cannot read it (" + unreadable + ") and has no usable backup (" +
              (b.usable ? db_.lastError() : b.why) + "): running on the configuration file's values";
}

void Store::openInMemory(OpenResult& r, bool loadFile) {
  // Last resort: an in-memory database keeps the API working (overrides,
  // events, charts for this session); nothing survives a restart.
  const std::string why = db_.lastError();
  db_.close();
  inMemory_ = true;
  r.inMemory = true;
  r.ok = false;
  r.message += (r.message.empty() ? "" : "; ") + std::string("cannot use database ") + path_ + " (" + why +
               "): running without persistence";
  int rc = db_.open(":memory:");
  // A read-only state directory (read-only root file systems exist) still
  // lets us read the last checkpoint: copy the file into memory.
  bool loaded = false;
  if (rc == SQLITE_OK && loadFile) {
    loaded = store::copyInto(db_, path_, "immutable=1") == SQLITE_OK;
    if (loaded)
      r.message += "; last saved state loaded read-only";
    else
      rc = db_.open(":memory:");  // a fresh one: the copy may be half done
  }
  // A damaged file that could not be moved aside: the verified backup, then.
  if (rc == SQLITE_OK && !loaded) {
    const store::BackupCheck b = store::checkBackup(backupPath(), store::kSchemaVersion);
    if (b.usable && store::copyInto(db_, backupPath(), "mode=ro") == SQLITE_OK) {
      r.backupUsed = backupPath();
      r.backupTakenAtMs = b.mtimeMs;
      r.message += "; the backup " + backupPath() + " of " + utcMinute(b.mtimeMs) + " loaded read-only";
    } else if (b.usable) {
      rc = db_.open(":memory:");
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

}  // namespace xr
