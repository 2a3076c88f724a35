#pragma once
// Makes the hourly trend rows (core/trend_rows.h) from one sample a second:
// min, mean and max of each value over the hour, NaN readings left out. Pure;
// the store writes each finished hour in one transaction (not one per
// sample: docs/performance.md "Storage writes").
#include <array>
#include <cstdint>
#include <optional>

#include "core/trend_rows.h"

namespace xr {

class TrendTally {
 public:
  using Values = std::array<double, kTrendSeriesCount>;
  // One sample at unixMs; dayS: the local midnight of its day. Returns the
  // hour that ended before this sample (the clock moved to another hour,
  // forward or back), if it holds any sample.
  std::optional<TrendRow> add(std::int64_t unixMs, std::int64_t dayS, const Values& v);
  // The hour so far (nullopt before the first sample).
  std::optional<TrendRow> current() const;
  // Carry on an hour saved by an earlier run (a restart keeps its figures).
  void restore(const TrendRow& r);

 private:
  struct Acc {
    double min = NAN, max = NAN, sum = 0.0;
    std::int64_t n = 0;
  };
  std::int64_t hourS_ = -1;
  std::int64_t dayS_ = 0;
  std::int64_t samples_ = 0;
  std::array<Acc, kTrendSeriesCount> acc_{};
};

}  // namespace xr
