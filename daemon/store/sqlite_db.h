#pragma once
// A thin RAII wrapper of our own over the SQLite C API: Db owns a connection,
// Stmt a prepared statement. Nothing throws: every call returns the SQLite
// result code and the Db keeps the last error text.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

struct sqlite3;
struct sqlite3_stmt;

namespace xr::sql {

class Db {
 public:
  Db() = default;
  ~Db();
  Db(const Db&) = delete;
  Db& operator=(const Db&) = delete;
  Db(Db&& o) noexcept;
  Db& operator=(Db&& o) noexcept;

  // flags: SQLITE_OPEN_* (default read-write + create). Returns the result code.
  int open(const std::string& path, int flags = 0);
  void close();
  bool isOpen() const { return db_ != nullptr; }
  sqlite3* handle() const { return db_; }

  // Runs one or more statements without results.
  int exec(std::string_view sql);
  // First column of the first row as int64/text (for PRAGMAs); rc via out.
  std::int64_t queryInt(std::string_view sql, int* rc = nullptr);
  std::string queryText(std::string_view sql, int* rc = nullptr);

  const std::string& lastError() const { return lastError_; }
  int setError(int rc, std::string_view what);

 private:
  sqlite3* db_ = nullptr;
  std::string lastError_;
};

class Stmt {
 public:
  Stmt(Db& db, std::string_view sql);
  ~Stmt();
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;

  bool ok() const { return stmt_ != nullptr; }
  int prepareRc() const { return prepareRc_; }

  Stmt& bind(int idx, double v);
  Stmt& bind(int idx, std::int64_t v);
  Stmt& bind(int idx, int v) { return bind(idx, static_cast<std::int64_t>(v)); }
  Stmt& bind(int idx, std::string_view v);
  Stmt& bindBlob(int idx, std::span<const std::uint8_t> v);
  Stmt& bindNull(int idx);

  // SQLITE_ROW, SQLITE_DONE or an error code (recorded in the Db).
  int step();
  int reset();

  double colDouble(int i) const;
  std::int64_t colInt(int i) const;
  std::string colText(int i) const;
  bool colIsNull(int i) const;
  std::span<const std::uint8_t> colBlob(int i) const;

 private:
  Db& db_;
  sqlite3_stmt* stmt_ = nullptr;
  int prepareRc_ = 0;
  int bindRc_ = 0;
};

// BEGIN IMMEDIATE ... COMMIT; rolls back in the destructor unless committed.
class Transaction {
 public:
  explicit Transaction(Db& db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  int beginRc() const { return beginRc_; }
  int commit();

 private:
  Db& db_;
  int beginRc_;
  bool done_ = false;
};

bool isOk(int rc);  // SQLITE_OK, SQLITE_ROW or SQLITE_DONE

}  // namespace xr::sql
