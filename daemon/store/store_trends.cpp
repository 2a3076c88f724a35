// Trends over a season (core/trend_rows.h): hourly rows as the service
// finishes each hour, and the day's row recomputed from its hours in the same
// transaction, so a day row never disagrees with the hours it sums.
#include <sqlite3.h>

#include <cmath>
#include <string>

#include "store/store.h"

namespace xr {

namespace {

// "battery_v_min, battery_v_mean, battery_v_max, ...", in kTrendSeries order.
std::string statColumns(const char* prefix = "") {
  std::string cols;
  for (const auto& t : kTrendSeries)
    for (const char* k : {"_min", "_mean", "_max"})
      cols += (cols.empty() ? "" : ", ") + std::string(prefix) + std::string(t.name) + k;
  return cols;
}

// The day's row from its hours: lowest minimum, highest maximum, and the mean
// weighted by each hour's samples (hours without a value left out).
std::string dayAggregate() {
  std::string sel = "SELECT ?1, ?1, sum(samples)";
  for (const auto& t : kTrendSeries) {
    const std::string n(t.name);
    sel += ", min(" + n + "_min), sum(" + n + "_mean * samples) / sum(CASE WHEN " + n +
           "_mean IS NULL THEN 0 ELSE samples END), max(" + n + "_max)";
  }
  return "INSERT OR REPLACE INTO trends_daily(t_s, day_s, samples, " + statColumns() + ") " + sel +
         " FROM trends_hourly WHERE day_s = ?1";
}

TrendRow rowFrom(const sql::Stmt& st) {
  TrendRow r;
  r.startS = st.colInt(0);
  r.dayS = st.colInt(1);
  r.samples = st.colInt(2);
  for (std::size_t i = 0; i < kTrendSeriesCount; ++i) {
    auto col = [&](int k) {
      const int c = 3 + static_cast<int>(i) * 3 + k;
      return st.colIsNull(c) ? NAN : st.colDouble(c);
    };
    r.stat[i] = {col(0), col(1), col(2)};
  }
  return r;
}

}  // namespace

StoreStatus Store::saveTrendHour(const TrendRow& r) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (!db_.isOpen()) return status(SQLITE_MISUSE, "saveTrendHour");
  std::string marks = "?1, ?2, ?3";
  for (std::size_t i = 0; i < 3 * kTrendSeriesCount; ++i) marks += ", ?" + std::to_string(i + 4);
  sql::Transaction tx(db_);
  int rc = tx.beginRc();
  if (rc == SQLITE_OK) {
    sql::Stmt st(db_, "INSERT OR REPLACE INTO trends_hourly(t_s, day_s, samples, " + statColumns() +
                          ") VALUES(" + marks + ")");
    st.bind(1, r.startS).bind(2, r.dayS).bind(3, r.samples);
    int idx = 4;
    for (const TrendStat& s : r.stat)
      for (double v : {s.min, s.mean, s.max}) {
        if (std::isfinite(v))
          st.bind(idx, v);
        else
          st.bindNull(idx);
        ++idx;
      }
    rc = st.step();
  }
  if (rc == SQLITE_DONE) {
    sql::Stmt st(db_, dayAggregate());
    rc = st.bind(1, r.dayS).step();
  }
  if (rc == SQLITE_DONE) rc = tx.commit();
  return status(rc, "saveTrendHour");
}

std::optional<TrendRow> Store::findTrendHour(std::int64_t startS) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(db_, "SELECT t_s, day_s, samples, " + statColumns() + " FROM trends_hourly WHERE t_s = ?1");
  if (st.bind(1, startS).step() == SQLITE_ROW) return rowFrom(st);
  return std::nullopt;
}

std::vector<TrendRow> Store::trends(std::int64_t fromS, std::int64_t toS, bool daily) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  std::vector<TrendRow> out;
  sql::Stmt st(db_, "SELECT t_s, day_s, samples, " + statColumns() + " FROM " +
                        (daily ? "trends_daily" : "trends_hourly") +
                        " WHERE t_s >= ?1 AND t_s <= ?2 ORDER BY t_s");
  st.bind(1, fromS).bind(2, toS);
  while (st.ok() && st.step() == SQLITE_ROW) out.push_back(rowFrom(st));
  return out;
}

}  // namespace xr
