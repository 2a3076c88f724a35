#pragma once
// StoreService: the store thread's whole job in one object (non-RT). The
// runtime's store thread calls, in this order:
//
//   StoreService svc(settings.store);
//   auto start = svc.start(wallNowMs);          // open + restore
//   log start.message; if (start.alarm) raise an alarm event;
//   if (start.restored) regulator.restoreLedger(start.restored->ledger)
//       (before the RT thread starts, or as a command between ticks);
//   loop (>= 1 Hz, on its own thread):
//     svc.onEvents(events drained from the RT ring, wallNowMs, monoNow);
//     svc.onTelemetry(latest telemetry, latest ledger copy, monoNow, wallNowMs);
//   on stop (after the field is off): svc.stop(final ledger, wallNowMs);
//
// Errors never throw: each failure streak is reported once through the
// `report` callback (level + text) so the runtime logs it and raises an alarm,
// and again when writing works again.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "config/settings.h"
#include "core/events.h"
#include "core/telemetry.h"
#include "store/checkpoint_policy.h"
#include "store/store.h"

namespace xr {

struct StoreStart {
  OpenResult open;
  std::optional<SavedLedger> restored;  // the last checkpoint, if any
  bool alarm = false;                   // corrupt file replaced / running without persistence
  std::string message;                  // "restored ledger saved 2026-11-21T10:00:00Z (field_off): SoC ..."
};

class StoreService {
 public:
  using Report = std::function<void(EventLevel, const std::string&)>;
  explicit StoreService(const StoreSettings& settings, StoreOptions options = {}, Report report = {});

  StoreStart start(std::int64_t wallNowMs);
  // Latest telemetry and ledger copy: appends one history sample per wall
  // second and checkpoints when CheckpointPolicy says so.
  void onTelemetry(const Telemetry& t, const BatteryLedger& ledger, TimeNs monoNow, std::int64_t wallNowMs);
  // Events from the RT ring. Their monotonic stamps are mapped to wall time
  // through (monoNow, wallNowMs) when monoNow > 0, else stamped wallNowMs.
  void onEvents(std::span<const Event> events, std::int64_t wallNowMs, TimeNs monoNow = 0);
  // Final checkpoint + flush + close.
  StoreStatus stop(const BatteryLedger& ledger, std::int64_t wallNowMs);

  Store& store() { return store_; }
  int checkpoints() const { return checkpoints_; }
  CheckpointReason lastReason() const { return lastReason_; }

 private:
  void track(const StoreStatus& s, const char* what);

  StoreSettings settings_;
  Store store_;
  CheckpointPolicy policy_;
  Report report_;
  std::int64_t lastHistorySecond_ = INT64_MIN;
  bool failing_ = false;
  int checkpoints_ = 0;
  CheckpointReason lastReason_ = CheckpointReason::None;
};

// "2026-11-21T10:00:00Z" (UTC) for logs.
std::string formatUtc(std::int64_t unixMs);

}  // namespace xr
