#include "store/sqlite_db.h"

#include <sqlite3.h>

#include <utility>

namespace xr::sql {

bool isOk(int rc) { return rc == SQLITE_OK || rc == SQLITE_ROW || rc == SQLITE_DONE; }

Db::~Db() { close(); }

Db::Db(Db&& o) noexcept : db_(std::exchange(o.db_, nullptr)), lastError_(std::move(o.lastError_)) {}

Db& Db::operator=(Db&& o) noexcept {
  if (this != &o) {
    close();
    db_ = std::exchange(o.db_, nullptr);
    lastError_ = std::move(o.lastError_);
  }
  return *this;
}

int Db::open(const std::string& path, int flags) {
  close();
  if (flags == 0) flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
  flags |= SQLITE_OPEN_NOMUTEX;  // one connection, used by one thread
  const int rc = sqlite3_open_v2(path.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    setError(rc, "open " + path);
    sqlite3_close_v2(db_);
    db_ = nullptr;
    return rc;
  }
  sqlite3_extended_result_codes(db_, 1);
  return rc;
}

void Db::close() {
  if (db_) {
    sqlite3_close_v2(db_);
    db_ = nullptr;
  }
}

int Db::setError(int rc, std::string_view what) {
  lastError_ = std::string(what) + ": " + sqlite3_errstr(rc);
  // The connection's message only when it belongs to this error: an error we
  // raise ourselves (a newer schema) left "not an error" there, which read as
  // "datatype mismatch (not an error)" in the journal (docs/security.md).
  if (db_ && rc != SQLITE_OK && (sqlite3_extended_errcode(db_) & 0xff) == (rc & 0xff)) {
    const char* m = sqlite3_errmsg(db_);
    if (m && std::string_view(m) != sqlite3_errstr(rc)) lastError_ += std::string(" (") + m + ")";
  }
  return rc;
}

int Db::exec(std::string_view sql) {
  if (!db_) return setError(SQLITE_MISUSE, "exec on a closed database");
  const std::string s(sql);
  const int rc = sqlite3_exec(db_, s.c_str(), nullptr, nullptr, nullptr);
  if (rc != SQLITE_OK) setError(rc, "exec");
  return rc;
}

std::int64_t Db::queryInt(std::string_view sql, int* rcOut) {
  Stmt st(*this, sql);
  int rc = st.ok() ? st.step() : st.prepareRc();
  std::int64_t v = 0;
  if (rc == SQLITE_ROW) v = st.colInt(0);
  if (rcOut) *rcOut = rc;
  return v;
}

std::string Db::queryText(std::string_view sql, int* rcOut) {
  Stmt st(*this, sql);
  int rc = st.ok() ? st.step() : st.prepareRc();
  std::string v;
  if (rc == SQLITE_ROW) v = st.colText(0);
  if (rcOut) *rcOut = rc;
  return v;
}

Stmt::Stmt(Db& db, std::string_view sql) : db_(db) {
  if (!db.handle()) {
    prepareRc_ = SQLITE_MISUSE;
    db_.setError(prepareRc_, "prepare on a closed database");
    return;
  }
  prepareRc_ = sqlite3_prepare_v2(db.handle(), sql.data(), static_cast<int>(sql.size()), &stmt_, nullptr);
  if (prepareRc_ != SQLITE_OK) {
    db_.setError(prepareRc_, "prepare");
    sqlite3_finalize(stmt_);
    stmt_ = nullptr;
  }
}

Stmt::~Stmt() { sqlite3_finalize(stmt_); }

Stmt& Stmt::bind(int idx, double v) {
  if (stmt_ && bindRc_ == SQLITE_OK) bindRc_ = sqlite3_bind_double(stmt_, idx, v);
  return *this;
}
Stmt& Stmt::bind(int idx, std::int64_t v) {
  if (stmt_ && bindRc_ == SQLITE_OK) bindRc_ = sqlite3_bind_int64(stmt_, idx, v);
  return *this;
}
Stmt& Stmt::bind(int idx, std::string_view v) {
  if (stmt_ && bindRc_ == SQLITE_OK)
    bindRc_ = sqlite3_bind_text(stmt_, idx, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
  return *this;
}
Stmt& Stmt::bindBlob(int idx, std::span<const std::uint8_t> v) {
  if (stmt_ && bindRc_ == SQLITE_OK)
    bindRc_ = sqlite3_bind_blob(stmt_, idx, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
  return *this;
}
Stmt& Stmt::bindNull(int idx) {
  if (stmt_ && bindRc_ == SQLITE_OK) bindRc_ = sqlite3_bind_null(stmt_, idx);
  return *this;
}

int Stmt::step() {
  if (!stmt_) return prepareRc_ ? prepareRc_ : SQLITE_MISUSE;
  if (bindRc_ != SQLITE_OK) return db_.setError(bindRc_, "bind");
  const int rc = sqlite3_step(stmt_);
  if (rc != SQLITE_ROW && rc != SQLITE_DONE) db_.setError(rc, "step");
  return rc;
}

int Stmt::reset() {
  if (!stmt_) return SQLITE_MISUSE;
  bindRc_ = SQLITE_OK;
  sqlite3_clear_bindings(stmt_);
  return sqlite3_reset(stmt_);
}

double Stmt::colDouble(int i) const { return sqlite3_column_double(stmt_, i); }
std::int64_t Stmt::colInt(int i) const { return sqlite3_column_int64(stmt_, i); }
std::string Stmt::colText(int i) const {
  const unsigned char* t = sqlite3_column_text(stmt_, i);
  return t ? std::string(reinterpret_cast<const char*>(t),
                         static_cast<std::size_t>(sqlite3_column_bytes(stmt_, i)))
           : std::string();
}
bool Stmt::colIsNull(int i) const { return sqlite3_column_type(stmt_, i) == SQLITE_NULL; }
std::span<const std::uint8_t> Stmt::colBlob(int i) const {
  const void* p = sqlite3_column_blob(stmt_, i);
  const int n = sqlite3_column_bytes(stmt_, i);
  if (!p || n <= 0) return {};
  return {static_cast<const std::uint8_t*>(p), static_cast<std::size_t>(n)};
}

Transaction::Transaction(Db& db) : db_(db), beginRc_(db.exec("BEGIN IMMEDIATE")) {}

Transaction::~Transaction() {
  if (!done_ && beginRc_ == SQLITE_OK) db_.exec("ROLLBACK");
}

int Transaction::commit() {
  if (beginRc_ != SQLITE_OK) return beginRc_;
  const int rc = db_.exec("COMMIT");
  if (rc == SQLITE_OK) done_ = true;
  return rc;
}

}  // namespace xr::sql
