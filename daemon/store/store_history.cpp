// Store: chart history. Samples are buffered per minute (1 s table) and
// averaged per minute (1 min table), written in one transaction per flush,
// trimmed by compact() and read back binned by queryHistory().
#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "store/floor_div.h"
#include "store/history_encoding.h"
#include "store/schema.h"
#include "store/store.h"

namespace xr {

using store::floorDiv;

namespace {

constexpr int kSlots = store::kHistorySlots;  // samples per bucket: 60 s per 1 s-row, 60 min per 1 min-row

}  // namespace

std::vector<std::string> defaultHistorySeries() {
  return {"ibv_v", "bcur_a", "alt_a", "soc_pct", "temp_f", "duty_pct", "rpm", "target_v"};
}

int Store::seriesId(std::string_view name) {
  sql::Stmt ins(db_, "INSERT OR IGNORE INTO series(name) VALUES(?1)");
  ins.bind(1, name).step();
  sql::Stmt sel(db_, "SELECT id FROM series WHERE name = ?1");
  if (sel.bind(1, name).step() == SQLITE_ROW) {
    const auto id = sel.colInt(0);
    if (id >= 0 && id < store::kSeriesSlots) return static_cast<int>(id);
  }
  return -1;
}

void Store::closeMinute() {
  if (aggMinute_ < 0) return;
  const std::size_t n = opt_.historySeries.size();
  const std::int64_t hour = floorDiv(aggMinute_, 60) * 60;  // minute index -> hour bucket (in minutes)
  Bucket& b = pending1m_[hour * 60];
  if (b.data.empty()) b.data.assign(n * kSlots, NAN);
  const int slot = static_cast<int>(aggMinute_ - hour);
  for (std::size_t s = 0; s < n; ++s)
    if (aggCount_[s] > 0) b.data[s * kSlots + slot] = static_cast<float>(aggSum_[s] / aggCount_[s]);
  aggMinute_ = -1;
}

StoreStatus Store::appendHistory(std::int64_t tUnixMs, std::span<const double> values) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  const std::size_t n = opt_.historySeries.size();
  if (values.size() != n) return status(SQLITE_MISUSE, "appendHistory: wrong number of series");
  const std::int64_t sec = floorDiv(tUnixMs, 1000);
  const std::int64_t minute = floorDiv(sec, 60);
  Bucket& b = pending1s_[minute * 60];
  if (b.data.empty()) b.data.assign(n * kSlots, NAN);
  const int slot = static_cast<int>(sec - minute * 60);
  for (std::size_t s = 0; s < n; ++s) b.data[s * kSlots + slot] = static_cast<float>(values[s]);

  // Downsample on insert: the 1 min table gets each finished minute's mean.
  if (minute != aggMinute_) {
    closeMinute();
    aggMinute_ = minute;
    aggSum_.assign(n, 0.0);
    aggCount_.assign(n, 0);
  }
  for (std::size_t s = 0; s < n; ++s)
    if (std::isfinite(values[s])) {
      aggSum_[s] += values[s];
      ++aggCount_[s];
    }

  if (lastFlushS_ < 0) lastFlushS_ = sec;
  // The wall clock went back (NTP or a GPS correcting a Pi that booted on
  // its last saved time): the intervals count from here, or nothing would
  // be written until the clock caught up again, hours later
  // (docs/security.md "The clock"). What was buffered goes to the card
  // now, as at any discontinuity.
  if (sec < lastFlushS_) {
    lastFlushS_ = sec;
    lastCompactS_ = std::min(lastCompactS_, sec);
    return flushPending(false);
  }
  // The flush and the hourly trim happen as the wall clock enters a new
  // historyFlushS period (at :00, :10, ...), not historyFlushS after the
  // start: the day rows, the trend hour and the ledger's interval checkpoint
  // are written on the same boundaries, so their commits share the -shm
  // index pages and the WAL's last page that each lone commit dirties again
  // (docs/performance.md "Storage writes").
  const std::int64_t period = std::max<std::int64_t>(1, opt_.historyFlushS);
  if (floorDiv(sec, period) != floorDiv(lastFlushS_, period)) {
    lastFlushS_ = sec;
    StoreStatus st = flushPending(false);
    if (st && floorDiv(sec, 3600) != floorDiv(lastCompactS_, 3600)) {
      lastCompactS_ = sec;
      st = compact(tUnixMs);
    }
    return st;
  }
  return {};
}

int Store::writeBuckets(std::string_view table, std::map<std::int64_t, Bucket>& pending, std::int64_t) {
  const std::size_t n = opt_.historySeries.size();
  sql::Stmt sel(db_, "SELECT data FROM " + std::string(table) + " WHERE key = ?1");
  sql::Stmt ins(db_, "INSERT OR REPLACE INTO " + std::string(table) + "(key, data) VALUES(?1, ?2)");
  if (!sel.ok()) return sel.prepareRc();
  if (!ins.ok()) return ins.prepareRc();
  std::vector<float> row(kSlots);
  for (auto& [bucket, b] : pending) {
    for (std::size_t s = 0; s < n; ++s) {
      if (s >= seriesIds_.size() || seriesIds_[s] < 0) continue;  // no id: series not recorded
      const float* src = &b.data[s * kSlots];
      if (std::none_of(src, src + kSlots, [](float v) { return !std::isnan(v); })) continue;
      std::fill(row.begin(), row.end(), NAN);
      const std::int64_t key = bucket * store::kSeriesSlots + seriesIds_[s];
      const double step = store::historyStep(opt_.historySeries[s]);
      sel.reset();
      if (sel.bind(1, key).step() == SQLITE_ROW) store::decodeHistoryRow(sel.colBlob(0), step, row);
      for (int i = 0; i < kSlots; ++i)
        if (!std::isnan(src[i])) row[i] = src[i];
      ins.reset();
      const std::vector<std::uint8_t> blob = store::encodeHistoryRow(row, step);
      const int rc = ins.bind(1, key).bindBlob(2, blob).step();
      if (rc != SQLITE_DONE) return rc;
    }
  }
  return SQLITE_OK;
}

// The 1 s chart's ring (schema v6): a minute's row goes to its slot, merged
// with what the slot holds for the same minute, over a row of a minute
// kRingMinutes ago. Every row has the same length, so SQLite rewrites it in
// its page: no page is freed, none taken from the freelist.
int Store::writeRing(std::map<std::int64_t, Bucket>& pending) {
  const std::size_t n = opt_.historySeries.size();
  sql::Stmt sel(db_, "SELECT t_s, data FROM history_1s_ring WHERE slot = ?1");
  sql::Stmt up(db_,
               "INSERT INTO history_1s_ring(slot, t_s, data) VALUES(?1, ?2, ?3) "
               "ON CONFLICT(slot) DO UPDATE SET t_s = excluded.t_s, data = excluded.data");
  if (!sel.ok()) return sel.prepareRc();
  if (!up.ok()) return up.prepareRc();
  std::vector<float> row(kSlots);
  for (auto& [minuteS, b] : pending) {
    for (std::size_t s = 0; s < n; ++s) {
      if (s >= seriesIds_.size() || seriesIds_[s] < 0) continue;  // no id: series not recorded
      const float* src = &b.data[s * kSlots];
      if (std::none_of(src, src + kSlots, [](float v) { return !std::isnan(v); })) continue;
      const double step = store::historyStep(opt_.historySeries[s]);
      std::fill(row.begin(), row.end(), NAN);
      const std::int64_t slot = ringSlot(minuteS, seriesIds_[s]);
      sel.reset();
      if (sel.bind(1, slot).step() == SQLITE_ROW && sel.colInt(0) == minuteS)
        store::decodeHistoryRow(sel.colBlob(1), step, row);
      for (int i = 0; i < kSlots; ++i)
        if (!std::isnan(src[i])) row[i] = src[i];
      up.reset();
      const std::vector<std::uint8_t> blob = store::encodeHistoryRow(row, step);
      const int rc = up.bind(1, slot).bind(2, minuteS).bindBlob(3, blob).step();
      if (rc != SQLITE_DONE) return rc;
    }
  }
  return SQLITE_OK;
}

std::int64_t Store::ringSlot(std::int64_t minuteS, int seriesId) {
  const std::int64_t m = floorDiv(minuteS, 60);
  return (m - floorDiv(m, store::kRingMinutes) * store::kRingMinutes) * store::kSeriesSlots + seriesId;
}

StoreStatus Store::flushHistory() {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  return flushPending(true);
}

StoreStatus Store::flushPending(bool all) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  // The periodic flush writes a 1 min row only once its hour is complete:
  // rewriting the open hour's rows every flush would cost pages for data the
  // 1 s table already holds. flushHistory()/close() write everything.
  std::map<std::int64_t, Bucket> keep1m;
  if (!all && aggMinute_ >= 0) {
    const std::int64_t openHour = floorDiv(aggMinute_, 60) * 3600;
    for (auto it = pending1m_.lower_bound(openHour); it != pending1m_.end();) {
      keep1m.insert(std::move(*it));
      it = pending1m_.erase(it);
    }
  }
  StoreStatus st;
  if (!pending1s_.empty() || !pending1m_.empty()) {
    if (!db_.isOpen()) {
      st = status(SQLITE_MISUSE, "flushHistory");
    } else {
      sql::Transaction tx(db_);
      int rc = tx.beginRc();
      if (rc == SQLITE_OK) rc = writeRing(pending1s_);
      if (rc == SQLITE_OK) rc = writeBuckets("history_1m", pending1m_, 3600);
      if (rc == SQLITE_OK) rc = tx.commit();
      st = status(rc, "flushHistory");
    }
  }
  // On error the buffer is dropped anyway: bounded memory beats chart history.
  pending1s_.clear();
  pending1m_ = std::move(keep1m);
  return st;
}

StoreStatus Store::compact(std::int64_t nowUnixMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  if (!db_.isOpen()) return status(SQLITE_MISUSE, "compact");
  const std::int64_t nowS = floorDiv(nowUnixMs, 1000);
  sql::Transaction tx(db_);
  int rc = tx.beginRc();
  // The 1 s chart needs no trim: its ring rewrites the slot of the minute
  // kRingMinutes ago (writeRing).
  if (rc == SQLITE_OK) {
    sql::Stmt st(db_, "DELETE FROM history_1m WHERE key < ?1");
    rc = st.bind(1, (nowS - opt_.history1mKeepS - 3600) * store::kSeriesSlots).step();
  }
  if (rc == SQLITE_DONE) {
    sql::Stmt st(db_, "DELETE FROM trends_hourly WHERE t_s < ?1");
    rc = st.bind(1, nowS - opt_.trendsHourlyKeepS).step();
  }
  if (rc == SQLITE_DONE) {
    sql::Stmt st(db_, "DELETE FROM events WHERE id <= (SELECT max(id) FROM events) - ?1");
    rc = st.bind(1, opt_.maxEvents).step();
  }
  if (rc == SQLITE_DONE) rc = tx.commit();
  return status(rc, "compact");
}

std::vector<HistoryPoint> Store::queryHistory(std::string_view series, std::int64_t fromMs, std::int64_t toMs,
                                              std::int64_t stepMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  std::vector<HistoryPoint> out;
  const auto it = std::find(opt_.historySeries.begin(), opt_.historySeries.end(), series);
  if (it == opt_.historySeries.end() || toMs < fromMs || !db_.isOpen()) return out;
  const std::size_t s = static_cast<std::size_t>(it - opt_.historySeries.begin());
  if (s >= seriesIds_.size() || seriesIds_[s] < 0) return out;
  const std::int64_t newest =
      pending1s_.empty() ? toMs : std::max(toMs, (pending1s_.rbegin()->first + 60) * 1000);
  // The ring holds 48 h whatever a longer keep asks for.
  const std::int64_t keepS = std::min(opt_.history1sKeepS, (store::kRingMinutes - 60) * 60);
  const bool fine = stepMs < 60000 && fromMs >= (newest - keepS * 1000);
  const std::int64_t slotS = fine ? 1 : 60;
  const std::int64_t fromS = floorDiv(fromMs, 1000), toS = floorDiv(toMs, 1000);

  std::map<std::int64_t, float> points;  // t (s) -> value
  auto take = [&](std::int64_t bucket, const float* row) {
    for (int i = 0; i < kSlots; ++i) {
      const std::int64_t t = bucket + i * slotS;
      if (t >= fromS && t <= toS && !std::isnan(row[i])) points[t] = row[i];
    }
  };
  readHistoryRows(fine, seriesIds_[s], store::historyStep(series), fromS, toS,
                  [&](std::int64_t bucket, const float* row) { take(bucket, row); });
  for (const auto& [bucket, b] : fine ? pending1s_ : pending1m_) take(bucket, &b.data[s * kSlots]);

  const std::int64_t stepS = std::max<std::int64_t>(slotS, stepMs / 1000);
  if (stepS <= slotS) {
    for (const auto& [t, v] : points) out.push_back({t * 1000, v});
    return out;
  }
  std::int64_t bin = INT64_MIN;
  double sum = 0.0;
  int count = 0;
  for (const auto& [t, v] : points) {
    const std::int64_t b = fromS + floorDiv(t - fromS, stepS) * stepS;
    if (b != bin && count > 0) {
      out.push_back({bin * 1000, sum / count});
      sum = 0.0;
      count = 0;
    }
    bin = b;
    sum += v;
    ++count;
  }
  if (count > 0) out.push_back({bin * 1000, sum / count});
  return out;
}

}  // namespace xr

namespace xr {

// The stored rows of one series whose bucket may hold a point in [fromS, toS]:
// the 1 min table by its time keys, the 1 s ring by the slots of the minutes
// asked for (one range, or two where the ring wraps), each row checked for
// the minute it holds now.
void Store::readHistoryRows(bool fine, int seriesId, double step, std::int64_t fromS, std::int64_t toS,
                            const std::function<void(std::int64_t bucketS, const float* row)>& take) {
  std::vector<float> row(kSlots);
  if (!fine) {
    const std::int64_t spanS = 60 * kSlots;
    sql::Stmt st(
        db_, "SELECT key, data FROM history_1m WHERE key >= ?1 AND key <= ?2 AND key % ?3 = ?4 ORDER BY key");
    st.bind(1, floorDiv(fromS, spanS) * spanS * store::kSeriesSlots)
        .bind(2, toS * store::kSeriesSlots + store::kSeriesSlots - 1)
        .bind(3, store::kSeriesSlots)
        .bind(4, seriesId);
    while (st.ok() && st.step() == SQLITE_ROW)
      if (store::decodeHistoryRow(st.colBlob(1), step, row))
        take(floorDiv(st.colInt(0), store::kSeriesSlots), row.data());
    return;
  }
  const std::int64_t m0 = floorDiv(fromS, 60), m1 = floorDiv(toS, 60);
  std::vector<std::pair<std::int64_t, std::int64_t>> ranges;  // slot ranges, inclusive
  const std::int64_t last = store::kRingMinutes * store::kSeriesSlots - 1;
  if (m1 - m0 + 1 >= store::kRingMinutes) {
    ranges.emplace_back(0, last);
  } else {
    const std::int64_t a = ringSlot(m0 * 60, 0), b = ringSlot(m1 * 60, store::kSeriesSlots - 1);
    if (a <= b) {
      ranges.emplace_back(a, b);
    } else {
      ranges.emplace_back(a, last);
      ranges.emplace_back(0, b);
    }
  }
  sql::Stmt st(db_,
               "SELECT t_s, data FROM history_1s_ring WHERE slot >= ?1 AND slot <= ?2 AND slot % ?3 = ?4");
  for (const auto& [lo, hi] : ranges) {
    st.reset();
    st.bind(1, lo).bind(2, hi).bind(3, store::kSeriesSlots).bind(4, seriesId);
    while (st.ok() && st.step() == SQLITE_ROW) {
      const std::int64_t minuteS = st.colInt(0);
      if (minuteS < m0 * 60 || minuteS > m1 * 60) continue;  // an older round of the ring
      if (store::decodeHistoryRow(st.colBlob(1), step, row)) take(minuteS, row.data());
    }
  }
}

}  // namespace xr
