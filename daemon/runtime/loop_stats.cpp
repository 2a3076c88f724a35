#include "runtime/loop_stats.h"

#include <algorithm>
#include <cmath>

namespace xr::rt {

void LatencyHistogram::add(TimeNs v) noexcept {
  if (v < 0) v = -v;  // early wake-ups count as error too
  const auto bin = static_cast<std::size_t>(v / kBinNs);
  ++bins_[std::min(bin, kBins)];
  ++count_;
  max_ = std::max(max_, v);
}

TimeNs LatencyHistogram::quantile(double p) const noexcept {
  if (count_ == 0) return 0;
  p = std::clamp(p, 0.0, 1.0);
  // Rank of the sample (1-based) that the quantile names.
  const auto rank =
      std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(p * static_cast<double>(count_))));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i <= kBins; ++i) {
    seen += bins_[i];
    if (seen >= rank) return i == kBins ? max_ : std::min<TimeNs>(static_cast<TimeNs>(i + 1) * kBinNs, max_);
  }
  return max_;
}

std::uint64_t LatencyHistogram::countBelow(TimeNs limit) const noexcept {
  const auto lastBin = static_cast<std::size_t>(std::max<TimeNs>(0, limit) / kBinNs);
  // Bins above the one holding max() are empty: stop there (the summary
  // asks seven limits up to 2.5 ms of mostly empty histograms).
  const std::size_t usedBins = std::min(static_cast<std::size_t>(max_ / kBinNs), kBins) + 1;
  std::uint64_t n = 0;
  for (std::size_t i = 0; i < std::min(lastBin, usedBins); ++i) n += bins_[i];
  return n;
}

void LoopStats::onPeriodError(TimeNs lateness) noexcept {
  periodMeasured_ = true;
  periodErr_.add(lateness);
}

void LoopStats::onSamples(TimeNs now, const std::array<std::uint32_t, 4>& adsNew, bool inaFresh) noexcept {
  for (std::size_t c = 0; c < 4; ++c) adsTotals_[c] += adsNew[c];
  onSampleTotals(now, adsTotals_, inaFresh);
}

void LoopStats::rollWindow(TimeNs now, const std::array<std::uint32_t, 4>& adsTotals) noexcept {
  const TimeNs elapsed = now - windowStart_;
  windowS_ = toSec(elapsed);
  for (std::size_t c = 0; c < 4; ++c) {
    // Unsigned difference: exact across a wrap of the totals, as the sum
    // of the per-tick differences was.
    const std::uint32_t n = adsTotals[c] - adsBase_[c];
    adsRate_[c] = n / windowS_;
  }
  adsBase_ = adsTotals;
  inaRate_ = inaCount_ / windowS_;
  inaCount_ = 0;
  windowStart_ = now;
}

namespace {
double us(TimeNs t) { return static_cast<double>(t) / 1000.0; }
}  // namespace

LoopStatsSummary LoopStats::summary() const noexcept {
  LoopStatsSummary s;
  s.ticks = ticks_;
  s.overruns = overruns_;
  s.overrunsOwn = overrunsOwn_;
  s.tickCpuP99Us = us(tickCpu_.quantile(0.99));
  s.tickCpuMaxUs = us(tickCpu_.max());
  s.periodMeasured = periodMeasured_;
  s.periodErrP50Us = us(periodErr_.quantile(0.50));
  s.periodErrP99Us = us(periodErr_.quantile(0.99));
  s.periodErrMaxUs = us(periodErr_.max());
  s.computeP50Us = us(compute_.quantile(0.50));
  s.computeP99Us = us(compute_.quantile(0.99));
  s.computeMaxUs = us(compute_.max());
  s.ioP50Us = us(io_.quantile(0.50));
  s.ioP99Us = us(io_.quantile(0.99));
  s.ioMaxUs = us(io_.max());
  for (std::size_t i = 0; i < kPeriodErrorEdgesUs.size(); ++i) {
    s.periodErrHist[i] = periodErr_.countBelow(fromUs(kPeriodErrorEdgesUs[i]));
  }
  s.periodErrHist.back() = periodErr_.count();
  s.adsChannelRateHz = adsRate_;
  s.ch1SampleRateHz = adsRate_[1];
  s.inaSampleRateHz = inaRate_;
  s.windowS = windowS_;
  s.adsEdges = edges_;
  s.edgeIoP99Us = us(edgeIo_.quantile(0.99));
  s.edgeIoMaxUs = us(edgeIo_.max());
  return s;
}

}  // namespace xr::rt
