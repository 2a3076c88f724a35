// A year of trends answered from the store (docs/performance.md "Trends"):
// the Trends page's year (365 daily rows), a year of hourly rows (8 760, the
// CSV export's worst case within its 800-day bound), and a month of hours,
// from a database holding two years of hourly rows written as the daemon
// writes them (one transaction per hour). Target: < 100 ms on the board.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "store/store.h"

namespace {

using namespace xr;

constexpr std::int64_t kEndS = 1'780'000'000 / 3600 * 3600;
constexpr std::int64_t kHours = 2 * 366 * 24;

struct Db {
  std::string dir = "/var/tmp/xr-trends-bench-" + std::to_string(::getpid());
  Store store;
  Db() {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    store.open(dir + "/state.db", kEndS * 1000);
    for (std::int64_t h = 0; h < kHours; ++h) {
      TrendRow r;
      r.startS = kEndS - (kHours - h) * 3600;
      r.dayS = r.startS / 86400 * 86400;
      r.samples = 3600;
      for (std::size_t i = 0; i < kTrendSeriesCount; ++i)
        r.stat[i] = {10.0 + static_cast<double>(h % 7), 12.0 + static_cast<double>(i),
                     14.0 + static_cast<double>(h % 5)};
      store.saveTrendHour(r);
    }
  }
  ~Db() {
    store.close();
    std::filesystem::remove_all(dir);
  }
};

Db& db() {
  static Db d;
  return d;
}

void BM_TrendsQuery(benchmark::State& state) {
  const std::int64_t days = state.range(0);
  const bool daily = state.range(1) != 0;
  Store& s = db().store;
  std::size_t rows = 0;
  for (auto _ : state) {
    const auto r = s.trends(kEndS - days * 86400, kEndS, daily);
    rows = r.size();
    benchmark::DoNotOptimize(r.data());
  }
  state.counters["rows"] = static_cast<double>(rows);
}
BENCHMARK(BM_TrendsQuery)
    ->ArgNames({"days", "daily"})
    ->Args({365, 1})
    ->Args({365, 0})
    ->Args({30, 0})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
