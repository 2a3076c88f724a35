#pragma once
// The SQLite store as the running daemon uses it, off the RT thread: one
// mutex around Store (the main/supervisor thread, the event pump and the web
// threads all reach it; the RT thread never does).
//   start : restore the ledger and the parameter overrides; a damaged, lost
//           or newer database is reported once as an event (StoreRestored,
//           StoreReset, StoreNewerSchema, StoreNotSaving)
//   1 Hz  : chart history; CheckpointPolicy decides when to save the ledger;
//           the daily verified backup
//   events: appended as the pump delivers them
//   stop  : final checkpoint ("stop")
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/stored_overrides.h"
#include "battery/ledger.h"
#include "config/hardware_choices.h"
#include "params/params.h"
#include "runtime/handoffs.h"
#include "runtime/wall_clock.h"
#include "store/checkpoint_policy.h"
#include "store/store.h"
#include "store/trend_tally.h"

namespace xr::app {

std::int64_t unixMsNow();

class StoreService {
 public:
  // options: the store's (tools/history_fill.cpp turns the daily backup off).
  StoreService(const std::string& path, int checkpointIntervalS, StoreOptions options = {});
  const OpenResult& openResult() const { return open_; }
  // The one wall clock (runtime/wall_clock.h) for every row from now on:
  // the simulated one in --sim. speed: how many clock seconds pass per
  // wall second (0 = unpaced), which widens the summaries' step. Before
  // the threads that use the store start.
  void useClock(const rt::WallClock& clock, double speed);
  // That clock's time (the system's before useClock).
  std::int64_t clockMs() const { return nowMs(); }

  std::optional<SavedLedger> loadLedger();
  // fileParams with the stored overrides that fit applied, checked as one
  // set (stored_overrides.h). Each dropped override is forgotten in the
  // store and recorded there as an OverrideDropped warning event.
  OverrideResolution applyOverrides(const Params& fileParams, const NameSet& fileNames);
  // One PATCH, in one transaction: forgets the stored dashboard values of
  // `dropped` (its nulls) and persists the names whose values differ
  // between before and after. Empty, or why the change could not be saved
  // (read-only file, in-memory fallback, a full disk, a failed row); then
  // nothing of it is saved, and the caller must not report success.
  std::string saveOverrides(const Params& fileParams, const Params& before, const Params& after,
                            const std::vector<std::string>& dropped = {});

  // For /api/system and the journal.
  struct Status {
    std::string path;
    bool persistent = false;   // false: running on the in-memory fallback
    bool recovered = false;    // the old file was damaged and set aside at start
    bool restored = false;     // ... and its data came back from the verified backup
    bool newerSchema = false;  // a newer release's file: read, left untouched, nothing saved
    std::string message;
    std::string backupPath;         // the verified copy (<path>.bak)
    std::int64_t lastBackupMs = 0;  // when it was last written (UTC ms; 0 = none this run)
  };
  Status status();

  void appendEvent(const Event& e);
  // An event of the daemon's own, already in words (a settings change).
  void appendRecord(const EventRecord& r);
  // Once a second from the supervisor.
  void housekeeping(const rt::RuntimeSnapshot& s, const BatteryLedger& ledger, bool ledgerValid);
  void stop(const BatteryLedger& ledger, bool ledgerValid);

  std::vector<EventRecord> queryEvents(std::size_t limit, std::optional<std::int64_t> beforeId);
  std::vector<HistoryPoint> queryHistory(const std::string& series, std::int64_t fromMs, std::int64_t toMs,
                                         std::int64_t stepMs);
  std::vector<std::string> series() const { return series_; }
  // The History page's summaries, newest first (store/charge_tally.h).
  std::vector<DaySummary> days(std::size_t n);
  std::vector<ChargeSummary> charges(std::size_t n);
  // The charges that started in [fromMs, toMs), oldest first, the open one too.
  std::vector<ChargeSummary> chargesBetween(std::int64_t fromMs, std::int64_t toMs);
  // [start, end) of a local calendar day "YYYY-MM-DD" in Unix ms; nullopt
  // when the text is no such day.
  static std::optional<std::pair<std::int64_t, std::int64_t>> dayBoundsMs(const std::string& day);
  // Trend rows with a start in [fromS, toS], hourly (this hour's so far
  // included) or daily (core/trend_rows.h).
  std::vector<TrendRow> trends(std::int64_t fromS, std::int64_t toS, bool daily);
  std::string token();
  // Small named strings kept with the state (the Signal K token).
  std::optional<std::string> loadValue(const std::string& key);
  void saveValue(const std::string& key, const std::string& value);
  // Small named documents (store_auth.h keeps the paired devices here).
  std::vector<std::pair<std::string, std::string>> documents(std::string_view prefix);
  bool putDocument(std::string_view key, std::string_view value);  // false: not saved
  bool eraseDocument(std::string_view key);
  // The set-up page's hardware choices (config/hardware_choices.h); saved
  // whole or not at all: "" when saved, else why not.
  HardwareChoices loadHardwareChoices();
  std::string saveHardwareChoices(const HardwareChoices& c);

  // The event code of a start that found the database not as it should be
  // (nullptr: a normal start).
  static const char* alarmCode(const OpenResult& o);

  // For the write-breakdown bench (tests/bench/store/): the store's connection.
  sqlite3* sqliteHandleForBench() { return store_.sqliteHandle(); }

 private:
  std::string unwritable() const;  // caller holds m_
  std::int64_t nowMs() const { return clock_ ? clock_->unixMs() : rt::WallClock::systemUnixMs(); }
  void recordOpenAlarm();
  // Once a second: the day and charge summaries, saved every minute and
  // whenever a day or a charge ends (caller holds m_).
  void tallySummaries(const rt::RuntimeSnapshot& s, std::int64_t nowMs);
  // Once a second: the hourly trend row, saved when its hour ends.
  void tallyTrends(const rt::RuntimeSnapshot& s, std::int64_t nowMs);
  void restoreSummaries(std::int64_t nowMs);  // at open (caller holds m_ or is the constructor)
  void saveSummaries();                       // at stop (caller holds m_)

  std::mutex m_;
  Store store_;
  OpenResult open_;
  CheckpointPolicy policy_;
  std::vector<std::string> series_;
  std::int64_t lastHistoryS_ = -1;
  ChargeTally tally_;  // the History page's day and charge summaries
  TrendTally trends_;  // the hour's trend row
  std::int64_t lastSummarySaveMs_ = 0;
  const rt::WallClock* clock_ = nullptr;  // nullptr: the system clock
};

}  // namespace xr::app
