#include "store/trend_tally.h"

#include <algorithm>

#include "store/floor_div.h"

namespace xr {

std::optional<TrendRow> TrendTally::add(std::int64_t unixMs, std::int64_t dayS, const Values& v) {
  const std::int64_t hour = store::floorDiv(store::floorDiv(unixMs, 1000), 3600) * 3600;
  std::optional<TrendRow> ended;
  if (hour != hourS_) {
    if (samples_ > 0) ended = current();
    hourS_ = hour;
    dayS_ = dayS;
    samples_ = 0;
    acc_ = {};
  }
  ++samples_;
  for (std::size_t i = 0; i < kTrendSeriesCount; ++i) {
    if (!std::isfinite(v[i])) continue;
    Acc& a = acc_[i];
    a.min = a.n ? std::min(a.min, v[i]) : v[i];
    a.max = a.n ? std::max(a.max, v[i]) : v[i];
    a.sum += v[i];
    ++a.n;
  }
  return ended;
}

std::optional<TrendRow> TrendTally::current() const {
  if (hourS_ < 0 || samples_ == 0) return std::nullopt;
  TrendRow r;
  r.startS = hourS_;
  r.dayS = dayS_;
  r.samples = samples_;
  for (std::size_t i = 0; i < kTrendSeriesCount; ++i)
    if (acc_[i].n > 0) r.stat[i] = {acc_[i].min, acc_[i].sum / static_cast<double>(acc_[i].n), acc_[i].max};
  return r;
}

void TrendTally::restore(const TrendRow& r) {
  hourS_ = r.startS;
  dayS_ = r.dayS;
  samples_ = r.samples;
  for (std::size_t i = 0; i < kTrendSeriesCount; ++i) {
    const TrendStat& s = r.stat[i];
    // The saved mean stands for every sample of the hour that had a value;
    // the store keeps one count per row, so that is the best weight known.
    acc_[i] =
        std::isfinite(s.mean) ? Acc{s.min, s.max, s.mean * static_cast<double>(r.samples), r.samples} : Acc{};
  }
}

}  // namespace xr
