// Store: small settings kept across restarts: named documents (tuning logs),
// the operator's parameter overrides and the web API token.
#include <sqlite3.h>

#include <cstdint>
#include <fstream>
#include <random>

#include "store/store.h"

namespace xr {

StoreStatus Store::changed(StoreStatus s) {
  if (s) settingsChanged_ = true;  // backupIfDue() copies them soon
  return s;
}

// ---------------------------------------------------------------- documents

StoreStatus Store::putBlob(std::string_view key, std::string_view value) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(
      db_, "INSERT INTO kv(key, value) VALUES(?1, ?2) ON CONFLICT(key) DO UPDATE SET value = excluded.value");
  return changed(status(st.bind(1, key).bind(2, value).step(), "putBlob"));
}

std::optional<std::string> Store::getBlob(std::string_view key) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(db_, "SELECT value FROM kv WHERE key = ?1");
  if (st.bind(1, key).step() == SQLITE_ROW) return st.colText(0);
  return std::nullopt;
}

std::vector<std::pair<std::string, std::string>> Store::blobsWithPrefix(std::string_view prefix) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  std::vector<std::pair<std::string, std::string>> out;
  // substr, not LIKE: a '%' or '_' in the prefix must not match anything.
  sql::Stmt st(db_, "SELECT key, value FROM kv WHERE substr(key, 1, length(?1)) = ?1 ORDER BY key");
  if (!st.bind(1, prefix).ok()) return out;
  while (st.step() == SQLITE_ROW) out.emplace_back(st.colText(0), st.colText(1));
  return out;
}

StoreStatus Store::eraseBlob(std::string_view key) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(db_, "DELETE FROM kv WHERE key = ?1");
  return changed(status(st.bind(1, key).step(), "eraseBlob"));
}

// ---------------------------------------------------------------- overrides

StoreStatus Store::setOverride(std::string_view name, std::string_view value, std::string_view fileValue,
                               std::int64_t nowUnixMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(db_,
               "INSERT INTO overrides(name, value, file_value, changed_at_ms) VALUES(?1, ?2, ?3, ?4) "
               "ON CONFLICT(name) DO UPDATE SET value = excluded.value, file_value = excluded.file_value, "
               "changed_at_ms = excluded.changed_at_ms");
  return changed(
      status(st.bind(1, name).bind(2, value).bind(3, fileValue).bind(4, nowUnixMs).step(), "setOverride"));
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
  return changed(status(st.bind(1, name).step(), "resetOverride"));
}

StoreStatus Store::inTransaction(const std::function<StoreStatus()>& fn) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Transaction tx(db_);
  if (tx.beginRc() != SQLITE_OK) return status(tx.beginRc(), "begin");
  if (StoreStatus s = fn(); !s) return s;  // tx rolls back as it goes
  return status(tx.commit(), "commit");
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

}  // namespace xr
