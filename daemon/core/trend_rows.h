#pragma once
// Trends over a season (docs/dashboard.md "Trends"): one row per hour, and
// one per day, of the minimum, mean and maximum of the values an owner
// follows over months. The store keeps them (store/trend_tally.h makes the
// hourly rows); the API sends them and exports them as CSV.
#include <array>
#include <cmath>
#include <cstdint>
#include <string_view>

namespace xr {

// The trended values, in row order: name (the API's and the CSV's) and unit.
struct TrendSeriesInfo {
  std::string_view name;
  std::string_view unit;
};
inline constexpr std::array<TrendSeriesInfo, 6> kTrendSeries = {{
    {"battery_v", "V"},
    {"battery_a", "A"},
    {"alt_a", "A"},
    {"alt_temp_c", "C"},
    {"battery_temp_c", "C"},
    {"soc_pct", "%"},
}};
inline constexpr std::size_t kTrendSeriesCount = kTrendSeries.size();

struct TrendStat {
  double min = NAN, mean = NAN, max = NAN;  // NaN: no reading in the period
};

struct TrendRow {
  std::int64_t startS = 0;  // Unix seconds: the hour's start, or the local day's midnight
  std::int64_t dayS = 0;    // the local day's midnight (Unix seconds) this row counts to
  std::int64_t samples = 0;
  std::array<TrendStat, kTrendSeriesCount> stat{};
};

}  // namespace xr
