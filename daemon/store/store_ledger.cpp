// Store: the battery ledger checkpoint (one transaction, synchronous=FULL) and
// its reload at start.
#include <sqlite3.h>

#include <cmath>
#include <map>

#include "store/store.h"

namespace xr {

StoreStatus Store::checkpoint(const BatteryLedger& ledger, std::string_view reason, std::int64_t nowUnixMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (!db_.isOpen()) return status(SQLITE_MISUSE, "checkpoint");
  db_.exec("PRAGMA synchronous = FULL");
  int rc;
  {
    sql::Transaction tx(db_);
    rc = tx.beginRc();
    if (rc == SQLITE_OK) {
      sql::Stmt st(db_,
                   "INSERT INTO ledger(name, value) VALUES(?1, ?2) "
                   "ON CONFLICT(name) DO UPDATE SET value = excluded.value");
      BatteryLedger copy = ledger;
      visitLedgerFields(copy, [&](const char* name, double& v) {
        if (rc != SQLITE_OK || !std::isfinite(v)) return;  // NaN: keep the last good value
        st.reset();
        const int s = st.bind(1, std::string_view(name)).bind(2, v).step();
        if (s != SQLITE_DONE) rc = s;
      });
    }
    if (rc == SQLITE_OK) {
      sql::Stmt meta(
          db_,
          "INSERT INTO ledger_meta(id, saved_at_ms, reason) VALUES(1, ?1, ?2) "
          "ON CONFLICT(id) DO UPDATE SET saved_at_ms = excluded.saved_at_ms, reason = excluded.reason");
      const int s = meta.bind(1, nowUnixMs).bind(2, reason).step();
      if (s != SQLITE_DONE) rc = s;
    }
    if (rc == SQLITE_OK) rc = tx.commit();
  }
  db_.exec("PRAGMA synchronous = NORMAL");
  return status(rc, "checkpoint");
}

std::optional<SavedLedger> Store::loadLedger() {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (!db_.isOpen()) return std::nullopt;
  SavedLedger out;
  std::map<std::string, double, std::less<>> values;
  {
    sql::Stmt st(db_, "SELECT name, value FROM ledger");
    if (!st.ok()) return std::nullopt;
    while (st.step() == SQLITE_ROW) values[st.colText(0)] = st.colDouble(1);
  }
  if (values.empty()) return std::nullopt;
  visitLedgerFields(out.ledger, [&](const char* name, double& v) {
    const auto it = values.find(std::string_view(name));
    if (it != values.end()) v = it->second;  // fields added later keep their defaults
  });
  out.ledger.valid = true;
  sql::Stmt meta(db_, "SELECT saved_at_ms, reason FROM ledger_meta WHERE id = 1");
  if (meta.ok() && meta.step() == SQLITE_ROW) {
    out.savedAtMs = meta.colInt(0);
    out.reason = meta.colText(1);
  }
  return out;
}
}  // namespace xr
