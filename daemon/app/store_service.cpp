#include "app/store_service.h"

#include <spdlog/spdlog.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>

#include "store/param_overrides.h"

namespace xr::app {

std::int64_t unixMsNow() { return rt::WallClock::systemUnixMs(); }

StoreService::StoreService(const std::string& path, int checkpointIntervalS, StoreOptions options)
    : store_(std::move(options)), policy_(checkpointIntervalS), series_(defaultHistorySeries()) {
  // The database holds the web token: never readable by other users, with or
  // without systemd's UMask (docs/security.md). umask is process-wide, but
  // this runs before any other thread of the daemon exists; SQLite gives the
  // -wal and -shm files the database file's mode.
  const mode_t oldMask = ::umask(077);
  open_ = store_.open(path, unixMsNow());
  ::umask(oldMask);
  for (const char* suffix : {"", "-wal", "-shm"}) {
    const std::string f = path + suffix;
    struct stat st {};
    if (store_.inMemory() || ::stat(f.c_str(), &st) != 0 || (st.st_mode & 0007) == 0) continue;
    if (::chmod(f.c_str(), st.st_mode & 0770) == 0)
      spdlog::warn("store: {} was readable by every user; access for others removed (it holds the web token)",
                   f);
    else
      spdlog::error("store: {} is readable by every user and cannot be changed: {}", f, std::strerror(errno));
  }
  recordOpenAlarm();
  // Today's totals so far keep counting; a charge the last run left open
  // ended when it stopped.
  restoreSummaries(unixMsNow());
}

void StoreService::useClock(const rt::WallClock& clock, double speed) {
  std::lock_guard lock(m_);
  clock_ = &clock;
  // Read once a wall second, a simulated clock moves by `speed` seconds; an
  // unpaced run by any amount (it never stops between two reads).
  if (clock.simulated()) tally_.setMaxStepS(speed > 0.0 ? kTallyMaxStepS * std::max(1.0, speed) : 1e12);
}

const char* StoreService::alarmCode(const OpenResult& o) {
  if (o.newerSchema) return "StoreNewerSchema";
  if (o.restored) return "StoreRestored";
  if (o.recovered) return "StoreReset";
  if (o.inMemory) return "StoreNotSaving";
  return nullptr;
}

void StoreService::recordOpenAlarm() {
  // Told once: the event is stored with the data it is about (in memory
  // too, so the dashboard's event list shows it for this run).
  const char* code = alarmCode(open_);
  if (!code || !store_.isOpen()) return;
  EventRecord e;
  e.tMs = nowMs();
  e.level = open_.restored ? "error" : "critical";
  e.code = code;
  e.reason = "NONE";
  e.message = open_.message;
  if (const StoreStatus st = store_.appendEvents(std::span<const EventRecord>(&e, 1)); !st)
    spdlog::warn("store: event not saved: {}", st.error);
}

std::optional<SavedLedger> StoreService::loadLedger() {
  std::lock_guard lock(m_);
  return store_.loadLedger();
}

OverrideResolution StoreService::applyOverrides(const Params& fileParams, const NameSet& fileNames) {
  std::lock_guard lock(m_);
  OverrideResolution r = resolveStoredOverrides(fileParams, fileNames, store_.overrides());
  const std::int64_t now = nowMs();
  for (const auto& d : r.dropped) {
    EventRecord e;
    e.tMs = now;
    e.level = "warning";
    e.code = "OverrideDropped";
    e.reason = "NONE";
    e.message = d.text();
    if (const StoreStatus st = store_.appendEvents(std::span<const EventRecord>(&e, 1)); !st)
      spdlog::warn("store: event not saved: {}", st.error);
    if (const StoreStatus st = store_.resetOverride(d.name); !st)
      spdlog::error("store: cannot forget the dropped override {}: {}", d.name, st.error);
  }
  return r;
}

// Why a settings change cannot be made durable now; "" when it can.
std::string StoreService::unwritable() const {
  if (!store_.inMemory() && store_.isOpen()) return "";
  return "the state database cannot be written (" + open_.message +
         "): the change would be lost at the next start";
}

std::string StoreService::saveOverrides(const Params& fileParams, const Params& before, const Params& after,
                                        const std::vector<std::string>& dropped) {
  std::lock_guard lock(m_);
  if (std::string why = unwritable(); !why.empty()) return why;
  const std::int64_t now = nowMs();
  const StoreStatus st = store_.inTransaction([&]() -> StoreStatus {
    for (const auto& name : dropped)
      if (StoreStatus s = store_.resetOverride(name); !s) {
        s.error = "cannot forget " + name + ": " + s.error;
        return s;
      }
    for (const ParamSpec& spec : catalogue()) {
      bool changed = false;
      const std::size_t n = spec.kind == ParamKind::Table ? RPM_TABLE_SIZE : 1;
      for (std::size_t i = 0; i < n; ++i) changed |= spec.get(before, i) != spec.get(after, i);
      if (!changed) continue;
      if (StoreStatus s = saveParamOverride(store_, spec.name, fileParams, after, now); !s) {
        s.error = "cannot save " + std::string(spec.name) + ": " + s.error;
        return s;
      }
    }
    return StoreStatus{};
  });
  if (st) return "";
  spdlog::error("store: a settings change was not saved (nothing of it): {}", st.error);
  return st.error;
}

StoreService::Status StoreService::status() {
  std::lock_guard lock(m_);
  Status s;
  s.path = store_.path();
  s.persistent = store_.isOpen() && !store_.inMemory();
  s.recovered = open_.recovered;
  s.restored = open_.restored;
  s.newerSchema = open_.newerSchema;
  s.message = open_.message;
  s.backupPath = store_.backupPath();
  s.lastBackupMs = store_.lastBackupMs();
  return s;
}

void StoreService::appendEvent(const Event& e) {
  std::lock_guard lock(m_);
  Event clean = e;  // the events table wants numbers: NaN/inf values (e.g. a stale reading) become 0
  if (!std::isfinite(clean.a)) clean.a = 0.0;
  if (!std::isfinite(clean.b)) clean.b = 0.0;
  const std::int64_t now = nowMs();
  const StoreStatus st = store_.queueEvent(toEventRecord(clean, now), now);
  if (!st) spdlog::warn("store: event not saved: {}", st.error);
}

void StoreService::appendRecord(const EventRecord& r) {
  std::lock_guard lock(m_);
  const StoreStatus st = store_.queueEvent(r, nowMs());
  if (!st) spdlog::warn("store: event not saved: {}", st.error);
}

namespace {
double columnValue(const rt::RuntimeSnapshot& s, const std::string& name) {
  double out = std::nan("");
  visitTelemetryColumns(s.telemetry, s.start, [&](std::string_view n, const ColumnValue& v) {
    if (n != name) return;
    if (const double* d = std::get_if<double>(&v))
      out = *d;
    else if (const bool* b = std::get_if<bool>(&v))
      out = *b ? 1.0 : 0.0;
  });
  return out;
}
}  // namespace

void StoreService::housekeeping(const rt::RuntimeSnapshot& s, const BatteryLedger& ledger, bool ledgerValid) {
  std::lock_guard lock(m_);
  const std::int64_t now = nowMs();
  if (now / 1000 != lastHistoryS_) {
    lastHistoryS_ = now / 1000;
    std::vector<double> values;
    values.reserve(series_.size());
    for (const auto& name : series_) values.push_back(columnValue(s, name));
    const StoreStatus st = store_.appendHistory(now, values);
    if (!st) spdlog::warn("store: history not saved: {}", st.error);
  }
  if (const StoreStatus st = store_.flushEventsIfDue(now); !st)
    spdlog::warn("store: events not saved: {}", st.error);
  tallySummaries(s, now);
  tallyTrends(s, now);
  // On the wall clock's interval marks, with the chart flush and the day
  // rows (store/checkpoint_policy.h).
  const CheckpointReason why =
      policy_.poll(s.telemetry.now, now, s.telemetry.field_enable, s.telemetry.stage, false);
  if (why != CheckpointReason::None && ledgerValid) {
    const StoreStatus st = store_.checkpoint(ledger, toString(why), now);
    if (!st) spdlog::error("store: checkpoint ({}) failed: {}", toString(why), st.error);
  }
  if (const StoreStatus st = store_.backupIfDue(now); !st)
    spdlog::error("store: {} (the previous backup stays; retried in an hour)", st.error);
}

void StoreService::stop(const BatteryLedger& ledger, bool ledgerValid) {
  std::lock_guard lock(m_);
  saveSummaries();
  if (ledgerValid) {
    const StoreStatus st = store_.checkpoint(ledger, "stop", nowMs());
    if (!st) spdlog::error("store: final checkpoint failed: {}", st.error);
  }
  store_.flushHistory();
  store_.close();
}

std::vector<EventRecord> StoreService::queryEvents(std::size_t limit, std::optional<std::int64_t> beforeId) {
  std::lock_guard lock(m_);
  return beforeId ? store_.queryEventsBeforeId(limit, *beforeId) : store_.queryEvents(limit);
}

std::vector<HistoryPoint> StoreService::queryHistory(const std::string& series, std::int64_t fromMs,
                                                     std::int64_t toMs, std::int64_t stepMs) {
  std::lock_guard lock(m_);
  return store_.queryHistory(series, fromMs, toMs, stepMs);
}

std::string StoreService::token() {
  std::lock_guard lock(m_);
  return store_.getOrCreateToken();
}

std::optional<std::string> StoreService::loadValue(const std::string& key) {
  std::lock_guard lock(m_);
  return store_.getBlob(key);
}

void StoreService::saveValue(const std::string& key, const std::string& value) {
  std::lock_guard lock(m_);
  store_.putBlob(key, value);
}

std::vector<std::pair<std::string, std::string>> StoreService::documents(std::string_view prefix) {
  std::lock_guard lock(m_);
  return store_.blobsWithPrefix(prefix);
}

bool StoreService::putDocument(std::string_view key, std::string_view value) {
  std::lock_guard lock(m_);
  // A pairing that would be gone after a restart is no pairing: refuse it.
  return unwritable().empty() && static_cast<bool>(store_.putBlob(key, value));
}

bool StoreService::eraseDocument(std::string_view key) {
  std::lock_guard lock(m_);
  // A revocation is a write like any other: one that a restart would undo
  // (a database read into memory because it cannot be written) gives the
  // phone its access back, so it goes through the same gate as PATCH.
  return unwritable().empty() && static_cast<bool>(store_.eraseBlob(key));
}

HardwareChoices StoreService::loadHardwareChoices() {
  std::lock_guard lock(m_);
  return {store_.getBlob(kChoiceBatteryTempSensor), store_.getBlob(kChoiceBmsInterface),
          parseChoiceNumber(store_.getBlob(kChoicePulleyRatio))};
}

std::string StoreService::saveHardwareChoices(const HardwareChoices& c) {
  std::lock_guard lock(m_);
  if (std::string why = unwritable(); !why.empty()) return why;
  auto put = [&](const char* key, const std::optional<std::string>& v) {
    return v ? store_.putBlob(key, *v) : store_.eraseBlob(key);
  };
  const StoreStatus st = store_.inTransaction([&]() -> StoreStatus {
    if (StoreStatus s = put(kChoiceBatteryTempSensor, c.batteryTempSensor); !s) return s;
    if (StoreStatus s = put(kChoiceBmsInterface, c.bmsInterface); !s) return s;
    return put(kChoicePulleyRatio, choiceNumberText(c.pulleyRatio));
  });
  if (st) return "";
  spdlog::error("store: the set-up's hardware choices were not saved: {}", st.error);
  return st.error;
}

}  // namespace xr::app
