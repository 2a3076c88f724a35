#include "store/store_service.h"

#include <ctime>
#include <string>

#include "store/history_sample.h"

namespace xr {

std::string formatUtc(std::int64_t unixMs) {
  const std::time_t t = static_cast<std::time_t>(unixMs / 1000);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

StoreService::StoreService(const StoreSettings& settings, StoreOptions options, Report report)
    : settings_(settings),
      store_(std::move(options)),
      policy_(settings.checkpoint_interval_s),
      report_(std::move(report)) {}

StoreStart StoreService::start(std::int64_t wallNowMs) {
  StoreStart s;
  s.open = store_.open(settings_.path, wallNowMs);
  s.alarm = s.open.alarm();
  s.message = s.open.message;
  if (store_.isOpen()) s.restored = store_.loadLedger();
  if (s.restored) {
    const auto& l = s.restored->ledger;
    s.message +=
        "; restored ledger saved " +
        (s.restored->savedAtMs > 0 ? formatUtc(s.restored->savedAtMs) : std::string("(time unknown)")) +
        " (" + s.restored->reason + "): CoulombCount " + std::to_string(l.CoulombCount_Ah) +
        " Ah, charged lifetime " + std::to_string(l.ChargedEnergy_AllTime_Wh) + " Wh, gain " +
        std::to_string(l.DynamicShuntGainFactor) + ", alt zero " + std::to_string(l.DynamicAltCurrentZero) +
        " A";
  } else {
    s.message += "; no saved ledger: starting from defaults";
  }
  if (report_) report_(s.alarm ? EventLevel::Error : EventLevel::Info, s.message);
  return s;
}

void StoreService::track(const StoreStatus& s, const char* what) {
  if (!s.ok && !failing_) {
    failing_ = true;
    if (report_)
      report_(EventLevel::Error,
              std::string("store ") + what + " failed" + (s.diskFull ? " (disk full)" : "") + ": " + s.error);
  } else if (s.ok && failing_) {
    failing_ = false;
    if (report_) report_(EventLevel::Info, std::string("store writes work again (") + what + ")");
  }
}

void StoreService::onTelemetry(const Telemetry& t, const BatteryLedger& ledger, TimeNs monoNow,
                               std::int64_t wallNowMs) {
  const std::int64_t second = wallNowMs / 1000;
  if (second != lastHistorySecond_) {
    lastHistorySecond_ = second;
    const auto v = historyValues(t);
    track(store_.appendHistory(wallNowMs, v), "history");
  }
  const CheckpointReason r = policy_.poll(monoNow, t.field_enable, t.stage, false);
  if (r != CheckpointReason::None && ledger.valid) {
    lastReason_ = r;
    ++checkpoints_;
    track(store_.checkpoint(ledger, toString(r), wallNowMs), "checkpoint");
  }
}

void StoreService::onEvents(std::span<const Event> events, std::int64_t wallNowMs, TimeNs monoNow) {
  if (events.empty()) return;
  std::vector<EventRecord> recs;
  recs.reserve(events.size());
  for (const auto& e : events) {
    const std::int64_t t =
        (monoNow > 0 && e.t > 0 && e.t <= monoNow) ? wallNowMs - (monoNow - e.t) / 1000000 : wallNowMs;
    recs.push_back(toEventRecord(e, t));
  }
  track(store_.appendEvents(recs), "events");
}

StoreStatus StoreService::stop(const BatteryLedger& ledger, std::int64_t wallNowMs) {
  StoreStatus s;
  if (ledger.valid) {
    s = store_.checkpoint(ledger, toString(CheckpointReason::Stop), wallNowMs);
    lastReason_ = CheckpointReason::Stop;
    ++checkpoints_;
    track(s, "final checkpoint");
  }
  store_.close();
  return s;
}

}  // namespace xr
