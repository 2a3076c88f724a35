// disk_writes_breakdown: which of the store's writers puts how many bytes on
// the disk in an hour of steady running (docs/performance.md "Storage
// writes", the breakdown table). Not a Google Benchmark: a plain tool whose
// table the next engineer re-reads after a store change.
//
//   disk_writes_breakdown --state-db FILE [--condition cruising|anchor] [--hours H]
//
// FILE: a COPY of a database filled by xr_history_fill (a year: the 1 s chart
// window full, so the hourly trim deletes rows as on a boat); the run changes
// it. The daemon's own StoreService is fed once a simulated second (the real
// pattern), on a simulated clock, after 15 simulated minutes of warm-up.
// Each commit is named by the tables its statements touch (sqlite3_trace_v2)
// and charged with the WAL frames it appended (sqlite3_wal_hook) and the
// bytes the process sent to the block layer meanwhile (/proc/self/io
// write_bytes: the WAL, the -shm index, the database file). The WAL hook
// also runs the automatic checkpoint as SQLite's default hook would (same
// threshold), so the copy of WAL pages into the database file is its own
// line. Every 30 simulated seconds the file system is written back
// (syncfs), as the kernel would within 30 s of real time: a page written
// again after that is counted again, as on the card.
#include <fcntl.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>

#include "app/store_service.h"

using namespace xr;

namespace {

std::int64_t writeBytes() {
  std::ifstream f("/proc/self/io");
  std::string k;
  std::int64_t v = 0;
  while (f >> k >> v)
    if (k == "write_bytes:") return v;
  return 0;
}

struct Line {
  long commits = 0;
  long frames = 0;
  std::int64_t bytes = 0;
};

struct Accounting {
  std::map<std::string, Line> lines;
  std::string label;  // the writers of the transaction under way
  std::int64_t lastBytes = 0;
  int lastFrames = 0;
  int autoCheckpoint = 1000;
  bool counting = false;
  bool inTx = false;

  void reset() {
    lines.clear();
    lastBytes = writeBytes();
  }
};

// Which writer a statement belongs to, by the table it writes.
const char* writerOf(const std::string& sqlText) {
  struct Rule {
    const char* needle;
    const char* name;
  };
  static constexpr Rule kRules[] = {
      {"DELETE FROM history_1", "hourly trim (chart rows, trends, events)"},
      {"INTO history_1s", "1 s chart flush"},
      {"INTO history_1m", "1 min chart rows"},
      {"INTO ledger", "ledger checkpoint"},
      {"INTO history_days", "day and charge rows"},
      {"INTO history_charges", "day and charge rows"},
      {"UPDATE history_charges", "day and charge rows"},
      {"INTO trends_hourly", "trend hour (+ its day)"},
      {"INTO events", "events"},
      {"INTO kv", "kv documents"},
  };
  for (const auto& r : kRules)
    if (sqlText.find(r.needle) != std::string::npos) return r.name;
  return nullptr;
}

int onTrace(unsigned type, void* ctx, void*, void* x) {
  if (type != SQLITE_TRACE_STMT || x == nullptr) return 0;
  auto& acc = *static_cast<Accounting*>(ctx);
  const std::string sqlText = static_cast<const char*>(x);
  // A transaction begins: what was written since the last commit (a
  // reader's mark in the -shm index) is nobody's commit.
  if (acc.label.empty() && acc.counting && !acc.inTx) {
    const std::int64_t now = writeBytes();
    acc.lines["between commits"].bytes += now - acc.lastBytes;
    acc.lastBytes = now;
  }
  if (sqlText.rfind("BEGIN", 0) == 0) {
    acc.inTx = true;
    acc.label.clear();  // a transaction before that wrote nothing (no WAL hook) is nobody's
  }
  if (const char* w = writerOf(sqlText)) {
    if (acc.label.find(w) == std::string::npos)
      acc.label += (acc.label.empty() ? "" : " + ") + std::string(w);
  }
  return 0;
}

int onWal(void* ctx, sqlite3* db, const char* zDb, int nFrame) {
  auto& acc = *static_cast<Accounting*>(ctx);
  const int frames = nFrame >= acc.lastFrames ? nFrame - acc.lastFrames : nFrame;  // restarted WAL
  std::int64_t now = writeBytes();
  if (acc.counting) {
    Line& l = acc.lines[acc.label.empty() ? "other" : acc.label];
    ++l.commits;
    l.frames += frames;
    l.bytes += now - acc.lastBytes;
  }
  acc.label.clear();
  acc.inTx = false;
  acc.lastFrames = nFrame;
  acc.lastBytes = now;
  if (acc.autoCheckpoint > 0 && nFrame >= acc.autoCheckpoint) {
    int nLog = 0, nCkpt = 0;
    sqlite3_wal_checkpoint_v2(db, zDb, SQLITE_CHECKPOINT_PASSIVE, &nLog, &nCkpt);
    now = writeBytes();
    if (acc.counting) {
      Line& l = acc.lines["WAL checkpoint: copy into the database file"];
      ++l.commits;
      l.frames += nCkpt;
      l.bytes += now - acc.lastBytes;
    }
    acc.lastBytes = now;
  }
  return SQLITE_OK;
}

void fillTelemetry(Telemetry& t, bool cruising, long sec) {
  const double wobble = std::sin(sec / 37.0) * 0.05;
  t.now = fromSec(sec);
  t.rpm = cruising ? 1700.0 + wobble * 100.0 : 0.0;
  t.field_enable = cruising;
  t.stage = cruising ? ChargeStage::FLOAT : ChargeStage::IDLE;
  t.reason = cruising ? Reason::NONE : Reason::REASON_RPM_LOW;
  t.battery_v = cruising ? 13.5 + wobble : 12.6 + wobble;
  t.ibv_v = t.battery_v;
  t.alt_a = cruising ? 12.0 + wobble * 20.0 : 0.0;
  t.bcur_a = cruising ? 6.0 + wobble * 20.0 : -6.0 + wobble;
  t.temp_f = cruising ? 150.0 + wobble : 70.0;
  t.battery_temp_c = 20.0;
  t.soc_pct = 80.0 + wobble;
  t.battery.socSource = SocSource::Counted;
  t.duty_pct = cruising ? 40.0 + wobble * 10.0 : 0.0;
  t.target_v = 13.5;
}

}  // namespace

int main(int argc, char** argv) {
  std::string db, condition = "cruising";
  double hours = 2.0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--state-db")
      db = v;
    else if (k == "--condition")
      condition = v;
    else if (k == "--hours")
      hours = std::atof(v.c_str());
  }
  if (db.empty() || (condition != "cruising" && condition != "anchor") || !(hours > 0.0)) {
    std::fprintf(stderr,
                 "usage: disk_writes_breakdown --state-db COPY [--condition cruising|anchor] [--hours H]\n");
    return 64;
  }
  const bool cruising = condition == "cruising";
  std::int64_t nowMs = rt::WallClock::systemUnixMs();
  rt::WallClock clock;
  const std::int64_t t0 = nowMs;
  clock.followSimulation([&] { return (nowMs - t0) * 1'000'000; });
  StoreOptions opt;
  opt.backupIntervalS = 1LL << 40;  // the daily copy is the daemon bench's line (its size / 24)
  app::StoreService store(db, 300, opt);
  if (store.openResult().inMemory || !store.openResult().ok) {
    std::fprintf(stderr, "cannot open %s: %s\n", db.c_str(), store.openResult().message.c_str());
    return 74;
  }
  store.useClock(clock, 1.0);
  sqlite3* h = store.sqliteHandleForBench();
  Accounting acc;
  {
    sqlite3_stmt* st = nullptr;
    if (sqlite3_prepare_v2(h, "PRAGMA wal_autocheckpoint", -1, &st, nullptr) == SQLITE_OK &&
        sqlite3_step(st) == SQLITE_ROW)
      acc.autoCheckpoint = sqlite3_column_int(st, 0);
    sqlite3_finalize(st);
  }
  sqlite3_trace_v2(h, SQLITE_TRACE_STMT, onTrace, &acc);
  sqlite3_wal_hook(h, onWal, &acc);
  const std::string dir = db.find('/') == std::string::npos ? "." : db.substr(0, db.rfind('/'));
  const int dirFd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);

  rt::RuntimeSnapshot snap;
  BatteryLedger ledger;
  const long warmS = 900, runS = static_cast<long>(hours * 3600.0);
  std::int64_t totalFrom = 0;
  for (long sec = 0; sec < warmS + runS; ++sec) {
    if (sec == warmS) {
      if (dirFd >= 0) ::syncfs(dirFd);
      acc.reset();
      acc.counting = true;
      totalFrom = acc.lastBytes;
    }
    fillTelemetry(snap.telemetry, cruising, sec);
    ledger.CoulombCount_Ah = 100.0 + sec * (cruising ? 1e-3 : -1.6e-3);
    ledger.ChargedEnergy_AllTime_Wh += cruising ? 0.05 : 0.0;
    store.housekeeping(snap, ledger, true);
    nowMs += 1000;
    if (sec % 30 == 29 && dirFd >= 0) ::syncfs(dirFd);
  }
  const std::int64_t total = writeBytes() - totalFrom;
  const double perH = 3600.0 / static_cast<double>(runS);
  std::printf("%s, %.1f simulated h after 15 min warm-up, per hour (WAL autocheckpoint %d pages):\n",
              condition.c_str(), hours, acc.autoCheckpoint);
  std::printf("%-58s %9s %11s %12s %10s\n", "writer (one commit's tables)", "commits", "WAL frames",
              "write KB", "KB/commit");
  std::int64_t sum = 0;
  for (const auto& [name, l] : acc.lines) {
    sum += l.bytes;
    std::printf("%-58s %9.1f %11.1f %12.1f %10.1f\n", name.c_str(), l.commits * perH, l.frames * perH,
                l.bytes * perH / 1000.0, l.commits ? l.bytes / 1000.0 / l.commits : 0.0);
  }
  std::printf("%-58s %9s %11s %12.1f\n", "outside any commit (reads, the last partial second)", "", "",
              (total - sum) * perH / 1000.0);
  std::printf("%-58s %9s %11s %12.1f\n", "total write_bytes", "", "", total * perH / 1000.0);
  store.stop(ledger, true);
  if (dirFd >= 0) ::close(dirFd);
  return 0;
}
