// Storage writes: bytes written per hour of steady running at the default
// policy (checkpoint every [store] checkpoint_interval_s = 300 s, a chart
// sample every second flushed every historyFlushS = 300 s, a few events, a
// field-off checkpoint and a stage checkpoint each hour, hourly compaction).
// Simulated over compressed hours; the counters are what a real hour costs.
//
// write_chars: bytes passed to write()/pwrite() (/proc/self/io wchar): every
// WAL frame and every page copied back by WAL checkpoints. file_growth: main
// file + WAL size change. A 50 h warm-up at the real retention fills the 48 h
// 1 s window first, so the measured hours include its deletes and the full
// tree depth (the 1 min table keeps growing for a year; its cost per hour is
// flat).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/time.h"
#include "store/checkpoint_policy.h"
#include "store/store.h"

namespace {

constexpr int kWarmupH = 50;

std::int64_t procIo(const std::string& key) {
  std::ifstream f("/proc/self/io");
  std::string k;
  std::int64_t v;
  while (f >> k >> v)
    if (k == key + ":") return v;
  return -1;
}

std::int64_t fileSize(const std::string& p) {
  std::error_code ec;
  const auto s = std::filesystem::file_size(p, ec);
  return ec ? 0 : static_cast<std::int64_t>(s);
}

// Runs `hours` of simulated time starting at hour `startHour`.
void simulate(xr::Store& s, xr::CheckpointPolicy& policy, xr::BatteryLedger& l, int startHour, int hours) {
  const std::int64_t t0 = 1'700'000'000'000;
  std::vector<double> v(xr::defaultHistorySeries().size());
  for (int sec = startHour * 3600; sec < (startHour + hours) * 3600; ++sec) {
    const std::int64_t now = t0 + sec * 1000LL;
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = 13.0 + 0.01 * ((sec * 7 + i * 13) % 100);
    s.appendHistory(now, v);
    l.ChargedEnergy_AllTime_Wh += 0.3;
    l.socAccumulator_AllTime += 80.0;
    l.totalSocSampleTime_AllTime += 1.0;
    const int inHour = sec % 3600;
    const bool field = inHour < 3000;  // one field-off per hour
    const auto stage = inHour < 1800 ? xr::ChargeStage::BULK : xr::ChargeStage::ABSORPTION;
    if (inHour % 600 == 0) {
      xr::EventRecord e{0, now, "info", "StageChanged", "NONE", "CHARGING: bulk -> absorption", 0, 1};
      s.appendEvents(std::span<const xr::EventRecord>(&e, 1));
    }
    const auto r = policy.poll(xr::fromSec(sec), now, field, stage, false);
    if (r != xr::CheckpointReason::None) s.checkpoint(l, xr::toString(r), now);
  }
}

void BM_StorageBytesPerHour(benchmark::State& state) {
  char tmpl[] = "/tmp/xr-store-bench-XXXXXX";
  const std::string dir = mkdtemp(tmpl);
  const std::string db = dir + "/bench.db";
  double wcharPerHour = 0, growthPerHour = 0, writeBytesPerHour = 0;
  for (auto _ : state) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    xr::StoreOptions opt;  // defaults
    xr::Store s(opt);
    s.open(db, 1'700'000'000'000);
    xr::CheckpointPolicy policy(300);
    xr::BatteryLedger l;
    simulate(s, policy, l, 0, kWarmupH);  // warm-up: tables at their steady size
    s.flushHistory();
    const std::int64_t w0 = procIo("wchar"), b0 = procIo("write_bytes");
    const std::int64_t f0 = fileSize(db) + fileSize(db + "-wal");
    const int hours = static_cast<int>(state.range(0));
    simulate(s, policy, l, kWarmupH, hours);
    const std::int64_t w1 = procIo("wchar"), b1 = procIo("write_bytes");
    const std::int64_t f1 = fileSize(db) + fileSize(db + "-wal");
    wcharPerHour = static_cast<double>(w1 - w0) / hours;
    writeBytesPerHour = static_cast<double>(b1 - b0) / hours;
    growthPerHour = static_cast<double>(f1 - f0) / hours;
    s.close();
  }
  state.counters["write_chars_per_h"] = wcharPerHour;
  state.counters["write_bytes_per_h"] = writeBytesPerHour;
  state.counters["file_growth_per_h"] = growthPerHour;
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_StorageBytesPerHour)->Arg(12)->Iterations(1)->Unit(benchmark::kMillisecond);

// Cost of one ledger checkpoint (synchronous=FULL), for the store thread.
void BM_Checkpoint(benchmark::State& state) {
  char tmpl[] = "/tmp/xr-store-bench-XXXXXX";
  const std::string dir = mkdtemp(tmpl);
  xr::Store s;
  s.open(dir + "/c.db", 1'700'000'000'000);
  xr::BatteryLedger l;
  for (auto _ : state) {
    l.ChargedEnergy_AllTime_Wh += 1.0;
    s.checkpoint(l, "interval", 1'700'000'000'000);
  }
  s.close();
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_Checkpoint)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
