// StoreService: the History page's day and charge summaries and the trends
// over a season (docs/dashboard.md "History", "Trends"): tallied once a
// second, saved as days, charges and hours end, read back with the running
// figures of today, the open charge and this hour over the stored rows.
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <ctime>

#include "app/store_service.h"
#include "core/freshness.h"
#include "core/wall_time_text.h"

namespace xr::app {

namespace {

// The owner's calendar day, "YYYY-MM-DD", in the board's time zone.
std::string localDay(std::int64_t unixMs) { return wallTimeText(unixMs, "%Y-%m-%d", TimeZone::Local); }

// The alternator's temperature in C (the sensor reads F; below -40 F: none).
double altTempC(const Telemetry& t) {
  return std::isfinite(t.temp_f) && t.temp_f > -40.0 ? (t.temp_f - 32.0) / 1.8 : NAN;
}

// Unix seconds of the local midnight of a calendar day (mktime handles a
// day of 23 or 25 hours at a daylight-saving change).
std::int64_t midnightS(int year, int month, int mday) {
  std::tm tm{};
  tm.tm_year = year - 1900;
  tm.tm_mon = month - 1;
  tm.tm_mday = mday;
  tm.tm_isdst = -1;
  return static_cast<std::int64_t>(std::mktime(&tm));
}

std::int64_t localMidnightS(std::int64_t unixMs) {
  const std::time_t t = static_cast<std::time_t>(unixMs / 1000);
  std::tm tm{};
  localtime_r(&t, &tm);
  return midnightS(tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday);
}

// How often today's running totals and the open charge are saved (at each
// multiple of it on the wall clock): a power cut loses at most this much of them, as the chart history loses
// at most one flush (StoreOptions::historyFlushS); a day or a charge that ends is saved at once
// (docs/performance.md "Storage writes").
constexpr std::int64_t kSummarySaveMs = 600'000;

}  // namespace

std::optional<std::pair<std::int64_t, std::int64_t>> StoreService::dayBoundsMs(const std::string& day) {
  int y = 0, m = 0, d = 0;
  char tail = 0;
  if (day.size() != 10 || std::sscanf(day.c_str(), "%4d-%2d-%2d%c", &y, &m, &d, &tail) != 3)
    return std::nullopt;
  if (y < 1970 || y > 9999 || m < 1 || m > 12 || d < 1 || d > 31) return std::nullopt;
  const std::int64_t from = midnightS(y, m, d);
  if (localDay(from * 1000) != day) return std::nullopt;  // 2026-02-30: no such day
  return std::pair{from * 1000, midnightS(y, m, d + 1) * 1000};
}

void StoreService::restoreSummaries(std::int64_t nowMs) {
  // Today's totals so far keep counting; a charge the last run left open
  // ended when it stopped; this hour's trend figures carry on.
  if (auto d = store_.findDay(localDay(nowMs))) tally_.restoreDay(*d);
  store_.closeOpenCharges("STOPPED");
  if (auto h = store_.findTrendHour(nowMs / 1000 / 3600 * 3600)) trends_.restore(*h);
}

void StoreService::saveSummaries() {
  if (!tally_.day().day.empty()) store_.saveDay(tally_.day());
  if (auto open = tally_.charge()) {
    ChargeSummary c = *open;  // stays open: the next start closes it as STOPPED
    store_.saveCharge(c);
  }
  if (auto hour = trends_.current()) store_.saveTrendHour(*hour);
}

void StoreService::tallyTrends(const rt::RuntimeSnapshot& s, std::int64_t nowMs) {
  const Telemetry& t = s.telemetry;
  const TrendTally::Values v{t.battery_v > 0.0 ? t.battery_v : NAN,
                             t.bcur_a,
                             t.alt_a,
                             altTempC(t),
                             t.battery_temp_c,
                             socShown(t).pct};
  if (auto ended = trends_.add(nowMs, localMidnightS(nowMs), v))
    if (const StoreStatus st = store_.saveTrendHour(*ended); !st)
      spdlog::warn("store: trend hour: {}", st.error);
}

std::vector<TrendRow> StoreService::trends(std::int64_t fromS, std::int64_t toS, bool daily) {
  std::lock_guard lock(m_);
  std::vector<TrendRow> out = store_.trends(fromS, toS, daily);
  // The hour under way, so the newest point is this hour's, not the last saved.
  if (auto hour = trends_.current(); hour && !daily && hour->startS >= fromS && hour->startS <= toS) {
    if (!out.empty() && out.back().startS == hour->startS)
      out.back() = *hour;
    else if (out.empty() || out.back().startS < hour->startS)
      out.push_back(*hour);
  }
  return out;
}

std::vector<ChargeSummary> StoreService::chargesBetween(std::int64_t fromMs, std::int64_t toMs) {
  std::lock_guard lock(m_);
  std::vector<ChargeSummary> out = store_.chargesBetween(fromMs, toMs);
  const auto& open = tally_.charge();
  if (!open || open->startMs < fromMs || open->startMs >= toMs) return out;
  for (auto& c : out)
    if (open->id != 0 && c.id == open->id) {
      c = *open;
      return out;
    }
  out.push_back(*open);
  return out;
}

void StoreService::tallySummaries(const rt::RuntimeSnapshot& s, std::int64_t nowMs) {
  const Telemetry& t = s.telemetry;
  TallySample x;
  x.unixMs = nowMs;
  x.day = localDay(nowMs);
  x.altA = t.alt_a;
  x.batteryV = t.battery_v;
  x.batteryA = t.bcur_a;
  x.altTempC = altTempC(t);
  x.socPct = socShown(t).pct;
  x.stage = t.stage;
  x.fieldOn = t.field_enable;
  x.engineRunning = fresh::engineTurning(t.rpm);
  x.reason = t.reason;
  ChargeTally::Ended ended = tally_.add(x);
  // On the wall clock's 10-minute boundaries, with the chart's flush
  // (Store::appendHistory): commits in the same second share the pages of
  // the WAL index that each lone commit would dirty again.
  const bool due =
      nowMs / kSummarySaveMs != lastSummarySaveMs_ / kSummarySaveMs || nowMs < lastSummarySaveMs_;
  if (!due && !ended.day && !ended.charge) return;
  lastSummarySaveMs_ = nowMs;
  // One transaction for the day's and the charge's rows: one commit (a few
  // pages of the card) every 10 minutes, not two a minute.
  const StoreStatus st = store_.inTransaction([&]() -> StoreStatus {
    if (ended.day)
      if (StoreStatus r = store_.saveDay(*ended.day); !r) return r;
    if (ended.charge)
      if (StoreStatus r = store_.saveCharge(*ended.charge); !r) return r;
    if (StoreStatus r = store_.saveDay(tally_.day()); !r) return r;
    if (auto open = tally_.charge()) {
      ChargeSummary c = *open;
      StoreStatus r = store_.saveCharge(c);
      if (r) tally_.setChargeId(c.id);
      return r;
    }
    return StoreStatus{};
  });
  if (!st) spdlog::warn("store: day and charge summaries: {}", st.error);
}

// The stored rows with today's and the open charge's running totals over
// them: the page shows this second's figures, not the last minute's save.
std::vector<DaySummary> StoreService::days(std::size_t n) {
  std::lock_guard lock(m_);
  std::vector<DaySummary> out = store_.days(n);
  const DaySummary& today = tally_.day();
  if (today.day.empty()) return out;
  if (!out.empty() && out.front().day == today.day)
    out.front() = today;
  else if (out.empty() || out.front().day < today.day)
    out.insert(out.begin(), today);
  if (out.size() > n) out.resize(n);
  return out;
}

std::vector<ChargeSummary> StoreService::charges(std::size_t n) {
  std::lock_guard lock(m_);
  std::vector<ChargeSummary> out = store_.charges(n);
  const auto& open = tally_.charge();
  if (!open) return out;
  if (!out.empty() && open->id != 0 && out.front().id == open->id)
    out.front() = *open;
  else
    out.insert(out.begin(), *open);
  if (out.size() > n) out.resize(n);
  return out;
}

}  // namespace xr::app
