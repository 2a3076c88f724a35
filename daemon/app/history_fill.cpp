// xr_history_fill (a developer tool, not installed): fills a state database with a simulated season of
// cruising, through the daemon's own store code (StoreService::housekeeping,
// the call the running daemon makes once a second), so the History and Trends
// pages and their tests see rows made exactly as the daemon makes them, in
// seconds rather than a month of simulated running.
//
//   xr_history_fill --state-db FILE [--days N] [--fine-days N] [--seed N]
//
// The last --fine-days days are fed every 30 s, the older ones every 300 s
// (trend rows are the same; day totals integrate the same currents). A day
// of the model: at anchor overnight with a 4 A house load; on two days of
// three the engine runs 1-4 h from the morning and the alternator charges
// the 300 Ah bank (bulk, absorption, float) and warms up; at the engine stop
// the field goes off with REASON_RPM_LOW. The last sample is a minute before
// now, so "today" holds the morning so far.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <string>

#include "app/store_service.h"

using namespace xr;

namespace {

struct Boat {
  double socPct = 70.0;
  double altTempC = 25.0;
  bool wasRunning = false;
};

// The engine's run on day `d` (from its start in seconds after midnight,
// length in seconds); none on every third day.
bool engineRuns(long d, double secOfDay, unsigned seed) {
  const long k = d + static_cast<long>(seed);
  if (k % 3 == 2) return false;
  const double start = (7 + k % 4) * 3600.0, len = (1 + (k * 7) % 4) * 3600.0;
  return secOfDay >= start && secOfDay < start + len;
}

// One sample of the model after `dt` seconds, filled into t.
void step(Boat& b, Telemetry& t, bool running, double dt, double seasonC) {
  const double house = 4.0;
  double alt = 0.0;
  ChargeStage stage = b.socPct < 85.0   ? ChargeStage::BULK
                      : b.socPct < 99.0 ? ChargeStage::ABSORPTION
                                        : ChargeStage::FLOAT;
  if (running)
    alt = stage == ChargeStage::BULK         ? 95.0
          : stage == ChargeStage::ABSORPTION ? 25.0 + 60.0 * (99.0 - b.socPct) / 14.0
                                             : house + 1.0;
  const double batA = alt - house;
  b.socPct = std::clamp(b.socPct + batA * dt / 3600.0 / 300.0 * 100.0, 5.0, 100.0);
  const double heat = running ? 55.0 + 0.4 * alt : seasonC;
  b.altTempC += (heat - b.altTempC) * std::min(1.0, dt / 900.0);
  const double rest = 12.0 + 1.2 * b.socPct / 100.0;
  t.battery_v = running ? (stage == ChargeStage::BULK         ? std::min(14.4, rest + 1.2)
                           : stage == ChargeStage::ABSORPTION ? 14.4
                                                              : 13.5)
                        : rest - 0.02 * house;
  t.ibv_v = t.battery_v;
  t.alt_a = alt;
  t.bcur_a = batA;
  t.rpm = running ? 1800.0 : 0.0;
  t.temp_f = b.altTempC * 1.8 + 32.0;
  t.battery_temp_c = seasonC - 3.0;
  t.soc_pct = b.socPct;
  t.battery.socSource = SocSource::Counted;
  t.stage = running ? stage : ChargeStage::IDLE;
  t.field_enable = running;
  t.reason = running ? Reason::NONE : Reason::REASON_RPM_LOW;
  t.duty_pct = running ? 60.0 : 0.0;
  t.target_v = 14.4;
  b.wasRunning = running;
}

}  // namespace

int main(int argc, char** argv) {
  std::string db;
  long days = 30, fineDays = 30;
  unsigned seed = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--state-db")
      db = v;
    else if (k == "--days")
      days = std::atol(v.c_str());
    else if (k == "--fine-days")
      fineDays = std::atol(v.c_str());
    else if (k == "--seed")
      seed = static_cast<unsigned>(std::atol(v.c_str()));
    else
      db.clear(), i = argc;
  }
  if (db.empty() || days < 1 || days > 3660 || fineDays < 0) {
    std::fprintf(stderr,
                 "usage: xr_history_fill --state-db FILE [--days 1..3660] [--fine-days N] [--seed N]\n");
    return 64;
  }
  const std::int64_t endMs = rt::WallClock::systemUnixMs() - 60'000;
  const std::int64_t startMs = endMs - days * 86'400'000LL, fineFromMs = endMs - fineDays * 86'400'000LL;
  std::int64_t nowMs = startMs;
  rt::WallClock clock;
  // The clock reads nowMs (to within the millisecond between these two lines).
  const std::int64_t t0 = rt::WallClock::systemUnixMs();
  clock.followSimulation([&] { return (nowMs - t0) * 1'000'000; });
  StoreOptions opt;
  opt.backupIntervalS = 1LL << 40;  // no daily copy of a database being filled
  app::StoreService store(db, 300, opt);
  if (store.openResult().inMemory || !store.openResult().ok) {
    std::fprintf(stderr, "xr_history_fill: cannot open %s: %s\n", db.c_str(),
                 store.openResult().message.c_str());
    return 74;
  }
  store.useClock(clock, 60.0);  // the summaries integrate steps up to 300 s
  Boat boat;
  rt::RuntimeSnapshot snap;
  BatteryLedger ledger;
  long samples = 0;
  while (nowMs <= endMs) {
    const double dt = nowMs < fineFromMs ? 300.0 : 30.0;
    const std::time_t ts = static_cast<std::time_t>(nowMs / 1000);
    std::tm tm{};
    localtime_r(&ts, &tm);
    const double secOfDay = tm.tm_hour * 3600.0 + tm.tm_min * 60.0 + tm.tm_sec;
    const double seasonC = 18.0 + 8.0 * std::sin(2.0 * std::numbers::pi * tm.tm_yday / 365.0);
    step(boat, snap.telemetry, engineRuns(static_cast<long>(nowMs / 86'400'000), secOfDay, seed), dt,
         seasonC);
    store.housekeeping(snap, ledger, false);
    ++samples;
    nowMs += static_cast<std::int64_t>(dt * 1000.0);
  }
  store.stop(ledger, false);
  std::printf("xr_history_fill: %ld samples, %ld days into %s\n", samples, days, db.c_str());
  return 0;
}
