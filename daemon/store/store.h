#pragma once
// Store: the SQLite persistence of xregulatord. One
// database file: battery ledger + regulator state, parameter overrides,
// events, chart history, the web token.
//
// Threading: never call from the RT thread (calls block on disk I/O). Any
// number of non-RT threads may call (the store thread writes, HTTP threads
// query): one internal mutex serialises the calls on the one connection.
//
// Failure policy: nothing throws and nothing aborts, and the user's data
// (settings, lifetime energy, cycles, the web token) outlives a damaged file
// (docs/security.md). A verified copy `<path>.bak` is written at open, once a
// day and, as `<path>.bak-v<N>`, before a migration from schema N. A corrupt
// or unreadable file is moved aside (`<path>.corrupt-<UTC time>`) and the
// copy restored; without a usable copy a fresh database is started. A file of
// a newer schema (a downgrade) is never written, migrated or moved: it is
// read into memory and nothing is saved. A file that cannot be written at
// all (read-only directory) leaves the store running on an in-memory
// database. All of these are reported by OpenResult::alarm() so the daemon
// raises an event. Write errors (a full disk) come back as StoreStatus values.
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "battery/ledger.h"
#include "core/events.h"
#include "core/trend_rows.h"
#include "store/charge_tally.h"
#include "store/event_queue.h"
#include "store/event_record.h"
#include "store/sqlite_db.h"

namespace xr {

struct StoreStatus {
  bool ok = true;
  bool diskFull = false;  // SQLITE_FULL: the disk (or the page quota) is full
  int code = 0;           // SQLite result code
  std::string error;
  explicit operator bool() const { return ok; }
};

// The series the runtime records for charts, in appendHistory() order.
std::vector<std::string> defaultHistorySeries();

struct StoreOptions {
  int busyTimeoutMs = 2000;
  // History is buffered in memory and written in one transaction this often:
  // a power cut loses at most this much chart history (the ledger has its own
  // checkpoints), and the SD card sees a few pages per flush instead of a few
  // pages per second (docs/performance.md, storage writes).
  int historyFlushS = 600;
  std::int64_t history1sKeepS = 48 * 3600;          // 1 s resolution kept 48 h
  std::int64_t history1mKeepS = 366LL * 24 * 3600;  // 1 min resolution kept a year
  // Hourly trend rows kept two years (a season compared with the last);
  // daily rows are never trimmed (~100 KB a decade).
  std::int64_t trendsHourlyKeepS = 731LL * 24 * 3600;
  std::int64_t maxEvents = 50000;  // events table bounded too
  std::vector<std::string> historySeries = defaultHistorySeries();
  // Tests: PRAGMA max_page_count, to simulate a full disk (0 = unlimited).
  std::int64_t maxPageCount = 0;
  // A verified backup this often (of the wall clock), besides the one at open,
  // and soon after the settings changed (overrides, the token, paired
  // devices): they are rare and precious, and an owner who changes a setting
  // or pairs a phone expects it to survive a damaged card a minute later. The
  // short delay only merges a burst of changes into one copy
  // (docs/operations.md "The daemon's own backup").
  std::int64_t backupIntervalS = 24 * 3600;
  std::int64_t settingsBackupS = 10;
  // queueEvent(): at most one commit of events a second, repeats of one kind
  // thinned (store/event_queue.h).
  EventQueueOptions eventQueue;
};

struct OpenResult {
  bool ok = false;                   // the database file is open and up to date
  bool recovered = false;            // the old file was damaged or unreadable: kept aside (corruptCopy)
  bool restored = false;             // the data came back from the verified backup (backupUsed)
  bool newerSchema = false;          // a newer release's file: left untouched, read into memory
  bool inMemory = false;             // the file cannot be used at all: running in memory, nothing persists
  std::string message;               // what happened, for the log
  std::string corruptCopy;           // where the bad file was moved
  std::string backupUsed;            // the backup restored (or read, with newerSchema)
  std::int64_t backupTakenAtMs = 0;  // when that backup was written (UTC ms)
  std::string backupError;           // the backup at open failed (the store runs; the old copy stays)
  int fromVersion = 0;               // schema version found (0 = new file)
  bool alarm() const { return recovered || restored || inMemory || newerSchema; }
};

struct SavedLedger {
  BatteryLedger ledger;
  std::int64_t savedAtMs = 0;  // UTC ms of the checkpoint (0 = unknown, migrated data)
  std::string reason;          // "interval", "field_off", "stage", "stop", ...
};

struct OverrideRow {
  std::string name;
  std::string value;      // the operator's value
  std::string fileValue;  // the value in the TOML file when it was changed
  std::int64_t changedAtMs = 0;
};

// Formats a core event for the store (allocates: non-RT only).
EventRecord toEventRecord(const Event& e, std::int64_t tUnixMs);

struct HistoryPoint {
  std::int64_t tMs = 0;
  double value = 0.0;
};

class Store {
 public:
  explicit Store(StoreOptions options = {});
  ~Store();  // flushes buffered history
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  OpenResult open(const std::string& path, std::int64_t nowUnixMs);
  void close();
  bool isOpen() const { return db_.isOpen(); }
  bool inMemory() const { return inMemory_; }
  const std::string& path() const { return path_; }

  // ---- ledger / regulator state --------------------------------------------
  // Saves the whole ledger in one transaction with synchronous=FULL (it must
  // survive a power cut once this returns).
  StoreStatus checkpoint(const BatteryLedger& ledger, std::string_view reason, std::int64_t nowUnixMs);
  std::optional<SavedLedger> loadLedger();
  // Opaque named documents (control's tuning logs as JSON).
  StoreStatus putBlob(std::string_view key, std::string_view value);
  std::optional<std::string> getBlob(std::string_view key);
  // Every document whose key starts with prefix (paired devices: "device:"), by key.
  std::vector<std::pair<std::string, std::string>> blobsWithPrefix(std::string_view prefix);
  StoreStatus eraseBlob(std::string_view key);

  // ---- parameter overrides -------------------------------------------------
  StoreStatus setOverride(std::string_view name, std::string_view value, std::string_view fileValue,
                          std::int64_t nowUnixMs);
  std::vector<OverrideRow> overrides();
  std::optional<OverrideRow> findOverride(std::string_view name);
  // Forget the operator's value: the file value applies again.
  StoreStatus resetOverride(std::string_view name);
  // ---- day and charge summaries (store/charge_tally.h) ----------------------
  StoreStatus saveDay(const DaySummary& d);  // inserts or replaces the day's row
  std::optional<DaySummary> findDay(std::string_view day);
  std::vector<DaySummary> days(std::size_t n);  // newest first
  // Inserts (c.id == 0: c.id is set) or updates the charge's row.
  StoreStatus saveCharge(ChargeSummary& c);
  std::vector<ChargeSummary> charges(std::size_t n);  // newest first
  // The charges that started in [fromMs, toMs), oldest first (at most 1000).
  std::vector<ChargeSummary> chargesBetween(std::int64_t fromMs, std::int64_t toMs);
  // A charge still open when the daemon stopped ended then: `reason`.
  StoreStatus closeOpenCharges(std::string_view reason);

  // fn's writes as one transaction: committed when fn succeeds, rolled back
  // when it fails, so a change of several values is saved whole or not at all.
  StoreStatus inTransaction(const std::function<StoreStatus()>& fn);

  // ---- events ----------------------------------------------------------------
  // Written now, in one transaction.
  StoreStatus appendEvents(std::span<const EventRecord> events);
  // The running daemon's path (store/event_queue.h): queued, written at once
  // when no event was written in the last second, else by flushEventsIfDue()
  // (once a second), a query, a backup or close(). nowMs: the store's clock.
  // The status of a write made now (ok when only queued).
  StoreStatus queueEvent(const EventRecord& e, std::int64_t nowMs);
  StoreStatus flushEventsIfDue(std::int64_t nowMs);
  // Newest first; only events strictly before `beforeMs` when given.
  std::vector<EventRecord> queryEvents(std::size_t limit, std::optional<std::int64_t> beforeMs = {});
  // Newest first by insertion order, only ids < beforeId (stable paging even
  // when many events share a millisecond).
  std::vector<EventRecord> queryEventsBeforeId(std::size_t limit, std::int64_t beforeId);

  // ---- chart history ---------------------------------------------------------
  // One sample: values in options.historySeries order (NaN = no value).
  // Buffered; flushed every historyFlushS (of sample time) or by flushHistory().
  StoreStatus appendHistory(std::int64_t tUnixMs, std::span<const double> values);
  StoreStatus flushHistory();
  // Points of `series` in [fromMs, toMs], averaged into stepMs bins (step 0 or
  // < 1 s = raw 1 s points). Uses the 1 s table when the range lies within its
  // retention and step < 60 s, else the 1 min table. Includes buffered data.
  std::vector<HistoryPoint> queryHistory(std::string_view series, std::int64_t fromMs, std::int64_t toMs,
                                         std::int64_t stepMs);
  // Deletes history and events beyond their retention.
  StoreStatus compact(std::int64_t nowUnixMs);

  // ---- trends over a season (core/trend_rows.h, store_trends.cpp) -------------
  // Saves one hourly row (replacing that hour's) and refreshes its day's row
  // from the day's hours, in one transaction.
  StoreStatus saveTrendHour(const TrendRow& r);
  std::optional<TrendRow> findTrendHour(std::int64_t startS);
  // Rows with startS in [fromS, toS], oldest first: hourly, or daily.
  std::vector<TrendRow> trends(std::int64_t fromS, std::int64_t toS, bool daily);

  // ---- web token -------------------------------------------------------------
  // The stored token, or a new random 32-byte hex token stored now.
  std::string getOrCreateToken();

  // ---- backups (backup.h) ------------------------------------------------------
  std::string backupPath() const { return path_ + ".bak"; }
  // Writes the verified copy now (not in memory, not over a newer release's copy).
  StoreStatus backup(std::int64_t nowUnixMs);
  // backup() when backupIntervalS has passed since the last one, or
  // settingsBackupS after a settings change; a failure is retried an hour
  // later. ok and nothing done when not due.
  StoreStatus backupIfDue(std::int64_t nowUnixMs);
  std::int64_t lastBackupMs() const { return lastBackupMs_; }

  // ---- diagnostics -----------------------------------------------------------
  std::string integrityCheck();  // "ok" when healthy
  // The connection, for the write-breakdown bench's SQLite hooks only
  // (tests/bench/store/disk_writes_breakdown.cpp); the daemon never uses it.
  sqlite3* sqliteHandle() const { return db_.handle(); }
  const std::string& lastError() const { return db_.lastError(); }

 private:
  struct Bucket {
    std::vector<float> data;  // series-major: data[s * 60 + slot]
  };
  StoreStatus status(int rc, std::string_view what);
  StoreStatus changed(StoreStatus s);  // a settings write: marks them for the next backup
  int configureConnection();
  int configure();
  int restoreFromBackup(OpenResult& r, std::int64_t backupTakenAtMs);
  // open()'s steps (store_open.cpp).
  struct BackupProbe;
  int openAndConfigure(const std::string& path);
  int recoverDamaged(OpenResult& r, const std::string& damage, std::int64_t nowUnixMs, BackupProbe& bak,
                     bool& mayBackup);
  void finishOpen(OpenResult& r, int rc, bool existed, bool mayBackup, std::int64_t nowUnixMs);
  void openNewer(OpenResult& r, int version);
  void openInMemory(OpenResult& r, bool existed);
  int seriesId(std::string_view name);
  int writeBuckets(std::string_view table, std::map<std::int64_t, Bucket>& pending, std::int64_t bucketSpanS);
  int writeRing(std::map<std::int64_t, Bucket>& pending);  // the 1 s chart (schema v6)
  static std::int64_t ringSlot(std::int64_t minuteS, int seriesId);
  void readHistoryRows(bool fine, int seriesId, double step, std::int64_t fromS, std::int64_t toS,
                       const std::function<void(std::int64_t bucketS, const float* row)>& take);
  void closeMinute();
  StoreStatus flushPending(bool all);
  StoreStatus flushEvents(std::int64_t nowMs, bool all);

  mutable std::recursive_mutex mu_;
  StoreOptions opt_;
  sql::Db db_;
  std::string path_;
  bool inMemory_ = false;
  bool backupsAllowed_ = false;  // false: in memory, or a copy we must not replace
  std::int64_t lastBackupMs_ = 0;
  bool settingsChanged_ = false;      // since the last backup
  std::int64_t retryBackupAtMs_ = 0;  // after a failed backup
  std::vector<int> seriesIds_;
  std::map<std::int64_t, Bucket> pending1s_;  // key: minute start (s)
  std::map<std::int64_t, Bucket> pending1m_;  // key: hour start (s)
  std::int64_t aggMinute_ = -1;               // minute being averaged for the 1 min table
  std::vector<double> aggSum_;
  std::vector<int> aggCount_;
  std::int64_t lastFlushS_ = -1;
  std::int64_t lastCompactS_ = -1;
  EventQueue eventQueue_;
  std::int64_t eventNowMs_ = 0;  // the latest time queueEvent/flushEventsIfDue saw
};

}  // namespace xr
