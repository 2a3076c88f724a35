#pragma once
// Verified backup copies of the state database (docs/security.md): the user's
// settings, lifetime energy, cycles and web token must survive a damaged file
// or a downgrade. Copies are made with SQLite's online backup API (a
// consistent snapshot even while the source is in WAL mode), checked with
// PRAGMA integrity_check on a fresh connection, and only then moved over the
// previous copy (temp name, fsync, rename, fsync of the directory): a power
// cut during a backup leaves the old copy in place.
#include <cstdint>
#include <span>
#include <string>

#include "store/sqlite_db.h"

namespace xr::store {

// Writes a verified copy of src's main database to `path`, replacing the file
// there only when the copy checks out. The copy is a single self-contained
// file (rollback journal, not WAL) with the permission bits `mode` (it holds
// the web token: never readable by other users). Empty on success, else why.
// Tables named in rowsLeftOut are copied empty (their schema only): the
// daily copy leaves out what running rebuilds (chart history, hourly trends),
// so that it costs the SD card a few hundred KB a day instead of the whole
// file (docs/performance.md "Storage writes"). Empty: a page-for-page copy.
std::string writeVerifiedBackup(sql::Db& src, const std::string& path, unsigned mode,
                                std::span<const std::string> rowsLeftOut = {});

struct BackupCheck {
  bool usable = false;       // integrity_check "ok" and a schema we can read
  int version = 0;           // its PRAGMA user_version
  std::int64_t mtimeMs = 0;  // when it was written (UTC ms, file time)
  std::string why;           // what is wrong when not usable
};
// Opens `path` read-only and runs integrity_check. A schema newer than
// maxVersion is reported as not usable (it is a newer release's data).
BackupCheck checkBackup(const std::string& path, int maxVersion);

// PRAGMA user_version of the file at `path`, opened read-only without
// touching it (-1 when it cannot be read). For deciding before any write.
int peekVersion(const std::string& path);

// Copies the database file `fromPath` (opened read-only; `uriFlags` e.g.
// "mode=ro" or "immutable=1") into dst's main database, replacing its
// contents. Returns the SQLite result code (SQLITE_OK on success); the error
// text is left in dst.
int copyInto(sql::Db& dst, const std::string& fromPath, const char* uriFlags);

}  // namespace xr::store
