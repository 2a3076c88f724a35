#include "store/backup.h"

#include <fcntl.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

namespace xr::store {

namespace fs = std::filesystem;

namespace {

// A file name as an SQLite URI: '%', '?' and '#' would be read as escapes,
// the query and the fragment (sqlite.org/uri.html, section 3.1).
std::string fileUri(const std::string& path, const char* query) {
  std::string u = "file:";
  for (const char c : path) {
    if (c == '%')
      u += "%25";
    else if (c == '?')
      u += "%3f";
    else if (c == '#')
      u += "%23";
    else
      u += c;
  }
  if (query && *query) u += std::string("?") + query;
  return u;
}

bool openReadOnly(sql::Db& db, const std::string& path, const char* query) {
  return db.open(fileUri(path, query), SQLITE_OPEN_READONLY | SQLITE_OPEN_URI) == SQLITE_OK;
}

std::string errnoText(const std::string& what) { return what + ": " + std::strerror(errno); }

// fsync of a file or a directory by name.
bool syncPath(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

}  // namespace

int copyInto(sql::Db& dst, const std::string& fromPath, const char* uriFlags) {
  sql::Db src;
  if (!openReadOnly(src, fromPath, uriFlags)) return dst.setError(SQLITE_CANTOPEN, "open " + fromPath);
  sqlite3_backup* b = sqlite3_backup_init(dst.handle(), "main", src.handle(), "main");
  if (!b) return dst.setError(sqlite3_errcode(dst.handle()), "backup from " + fromPath);
  const int step = sqlite3_backup_step(b, -1);
  const int fin = sqlite3_backup_finish(b);
  if (step != SQLITE_DONE) return dst.setError(step, "copy from " + fromPath);
  if (fin != SQLITE_OK) return dst.setError(fin, "copy from " + fromPath);
  return SQLITE_OK;
}

namespace {

// A page-for-page copy through SQLite's online backup API.
std::string copyWhole(sql::Db& src, sql::Db& dst) {
  sqlite3_backup* b = sqlite3_backup_init(dst.handle(), "main", src.handle(), "main");
  if (!b) return "backup: " + std::string(sqlite3_errmsg(dst.handle()));
  const int step = sqlite3_backup_step(b, -1);
  const int fin = sqlite3_backup_finish(b);
  if (step != SQLITE_DONE || fin != SQLITE_OK) {
    dst.setError(step != SQLITE_DONE ? step : fin, "backup");
    return dst.lastError();
  }
  return {};
}

std::string quoted(const std::string& name) {
  std::string q = "\"";
  for (const char c : name) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

struct SchemaObject {
  std::string type, name, sql;
};

// The schema of every table, index, view and trigger, tables first (an
// index needs its table), in the order they were made.
std::vector<SchemaObject> schemaOf(sql::Db& dst) {
  std::vector<SchemaObject> out;
  sql::Stmt q(dst,
              "SELECT type, name, sql FROM src.sqlite_master WHERE sql IS NOT NULL AND name NOT LIKE "
              "'sqlite_%' ORDER BY type <> 'table', rowid");
  while (q.ok() && q.step() == SQLITE_ROW) out.push_back({q.colText(0), q.colText(1), q.colText(2)});
  return out;
}

// The schema and the rows of every table but those left out, read from the
// source file (attached to dst) in one read transaction: a consistent
// snapshot, as the backup API gives, while the daemon's connection is idle.
std::string copySelected(sql::Db& src, sql::Db& dst, std::span<const std::string> leftOut) {
  const char* file = sqlite3_db_filename(src.handle(), "main");
  if (!file || !*file) return "the database has no file to copy from";
  {
    sql::Stmt at(dst, "ATTACH DATABASE ?1 AS src");
    if (at.bind(1, std::string_view(file)).step() != SQLITE_DONE) return dst.lastError();
  }
  int rc = dst.exec("PRAGMA busy_timeout = 2000");
  if (rc == SQLITE_OK) rc = dst.exec("BEGIN");  // deferred: only a read lock on the source
  if (rc == SQLITE_OK) {
    const auto objects = schemaOf(dst);
    for (const auto& o : objects) {
      if (rc == SQLITE_OK) rc = dst.exec(o.sql);  // unqualified: made in main, the copy
      const bool copyRows =
          o.type == "table" && std::find(leftOut.begin(), leftOut.end(), o.name) == leftOut.end();
      if (rc == SQLITE_OK && copyRows)
        rc = dst.exec("INSERT INTO main." + quoted(o.name) + " SELECT * FROM src." + quoted(o.name));
    }
    if (rc == SQLITE_OK && objects.empty()) rc = dst.setError(SQLITE_EMPTY, "the source has no tables");
  }
  if (rc == SQLITE_OK) {
    const std::int64_t v = dst.queryInt("PRAGMA src.user_version", &rc);
    if (sql::isOk(rc)) rc = dst.exec("PRAGMA main.user_version = " + std::to_string(v));
  }
  if (rc == SQLITE_OK) rc = dst.exec("COMMIT");
  std::string why = rc == SQLITE_OK ? "" : dst.lastError();
  if (rc != SQLITE_OK) dst.exec("ROLLBACK");
  if (dst.exec("DETACH DATABASE src") != SQLITE_OK && why.empty()) why = dst.lastError();
  return why;
}

}  // namespace

std::string writeVerifiedBackup(sql::Db& src, const std::string& path, unsigned mode,
                                std::span<const std::string> rowsLeftOut) {
  if (!src.isOpen()) return "no database open";
  const std::string tmp = path + ".tmp";
  std::error_code ec;
  fs::remove(tmp, ec);
  fs::remove(tmp + "-journal", ec);
  // Created here, not by SQLite, so the mode is ours whatever the umask.
  const int fd = ::open(tmp.c_str(), O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC, mode);
  if (fd < 0) return errnoText("create " + tmp);
  const bool modeOk = ::fchmod(fd, mode) == 0;
  ::close(fd);
  if (!modeOk) {
    fs::remove(tmp, ec);
    return errnoText("chmod " + tmp);
  }
  std::string why;
  {
    sql::Db dst;
    if (dst.open(tmp) != SQLITE_OK)
      why = dst.lastError();
    else
      why = rowsLeftOut.empty() ? copyWhole(src, dst) : copySelected(src, dst, rowsLeftOut);
    // The copy carries the source's WAL flag in its header: make it one
    // self-contained file, readable without a -wal beside it.
    int rc = 0;
    if (why.empty() && dst.queryText("PRAGMA journal_mode = DELETE", &rc) != "delete")
      why = "journal_mode DELETE refused: " + dst.lastError();
  }
  if (why.empty()) {
    // Verify what is on disk, through a connection that never saw the pages.
    const BackupCheck c = checkBackup(tmp, 1 << 30);
    if (!c.usable) why = "the copy does not verify: " + c.why;
  }
  if (why.empty() && !syncPath(tmp, false)) why = errnoText("fsync " + tmp);
  if (why.empty()) {
    fs::rename(tmp, path, ec);
    if (ec) why = "rename " + tmp + ": " + ec.message();
  }
  if (!why.empty()) {
    fs::remove(tmp, ec);
    fs::remove(tmp + "-journal", ec);
    return why;
  }
  const fs::path dir = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
  if (!syncPath(dir.string(), true)) return errnoText("fsync " + dir.string());
  return {};
}

BackupCheck checkBackup(const std::string& path, int maxVersion) {
  BackupCheck c;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    c.why = errnoText(path);
    return c;
  }
  if (!S_ISREG(st.st_mode) || st.st_size == 0) {
    c.why = path + ": not a database file";
    return c;
  }
  c.mtimeMs = static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000 + st.st_mtim.tv_nsec / 1'000'000;
  sql::Db db;
  if (!openReadOnly(db, path, "mode=ro")) {
    c.why = db.lastError();
    return c;
  }
  int rc = 0;
  const std::string check = db.queryText("PRAGMA integrity_check", &rc);
  if (!sql::isOk(rc)) {
    c.why = db.lastError();
    return c;
  }
  if (check != "ok") {
    c.why = "integrity_check: " + check;
    return c;
  }
  c.version = static_cast<int>(db.queryInt("PRAGMA user_version", &rc));
  if (!sql::isOk(rc)) {
    c.why = db.lastError();
    return c;
  }
  if (c.version > maxVersion) {
    c.why = "schema v" + std::to_string(c.version) + " is newer than v" + std::to_string(maxVersion);
    return c;
  }
  c.usable = c.version > 0;  // version 0: an empty file, nothing to restore
  if (!c.usable) c.why = path + ": holds no data (schema v0)";
  return c;
}

int peekVersion(const std::string& path) {
  sql::Db db;
  // mode=ro reads the WAL too; immutable=1 (main file only) where a
  // read-only connection cannot set up the WAL index.
  for (const char* q : {"mode=ro", "immutable=1"}) {
    if (!openReadOnly(db, path, q)) continue;
    int rc = 0;
    const auto v = db.queryInt("PRAGMA user_version", &rc);
    if (sql::isOk(rc)) return static_cast<int>(v);
    db.close();
  }
  return -1;
}

}  // namespace xr::store
