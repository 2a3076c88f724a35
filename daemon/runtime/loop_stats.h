#pragma once
// Control-loop statistics (docs/architecture.md): period error histogram,
// compute and I/O time p50/p99/max, overruns, per-channel ADS sample rates.
// LoopStats lives on the RT thread (fixed arrays, no allocation); its plain
// LoopStatsSummary is published with every telemetry snapshot and logged
// once a minute by a non-RT thread.
#include <array>
#include <cstdint>

#include "core/time.h"

namespace xr::rt {

// Fixed-bin latency histogram: 10 µs bins up to 5.12 ms, then one overflow
// bin; the exact maximum is kept beside it.
class LatencyHistogram {
 public:
  static constexpr TimeNs kBinNs = 10'000;
  static constexpr std::size_t kBins = 512;

  void add(TimeNs v) noexcept;
  void reset() noexcept { *this = LatencyHistogram{}; }
  std::uint64_t count() const noexcept { return count_; }
  TimeNs max() const noexcept { return max_; }
  // Upper edge of the bin holding the p-quantile (p in 0..1), capped at
  // max(); 0 when empty. Resolution is one bin (10 µs).
  TimeNs quantile(double p) const noexcept;
  // Samples with value < limit (limit rounded to the bin grid).
  std::uint64_t countBelow(TimeNs limit) const noexcept;

 private:
  std::array<std::uint32_t, kBins + 1> bins_{};
  std::uint64_t count_ = 0;
  TimeNs max_ = 0;
};

// Coarse period-error histogram edges published with the summary (µs).
inline constexpr std::array<int, 7> kPeriodErrorEdgesUs{10, 50, 100, 200, 500, 1000, 2500};

struct LoopStatsSummary {
  std::uint64_t ticks = 0;
  std::uint64_t overruns = 0;  // deadlines missed entirely
  // Of them, those the daemon caused: the tick itself (read, step, write)
  // outlasted a period. The others were missed while the thread waited to
  // run (a late wake-up: another process had the CPU).
  std::uint64_t overrunsOwn = 0;
  // The control thread's CPU time per tick (CLOCK_THREAD_CPUTIME_ID): what
  // "own" is judged on; 0 when not measured.
  double tickCpuP99Us = 0, tickCpuMaxUs = 0;
  bool periodMeasured = false;  // false under --speed max (no deadlines)
  double periodErrP50Us = 0, periodErrP99Us = 0, periodErrMaxUs = 0;
  double computeP50Us = 0, computeP99Us = 0, computeMaxUs = 0;
  double ioP50Us = 0, ioP99Us = 0, ioMaxUs = 0;
  // periodErrHist[i] = ticks with error < kPeriodErrorEdgesUs[i] (cumulative
  // counts); the last entry is every tick.
  std::array<std::uint64_t, kPeriodErrorEdgesUs.size() + 1> periodErrHist{};
  double ch1SampleRateHz = 0;                // alternator current (CH1)
  std::array<double, 4> adsChannelRateHz{};  // every ADS channel
  double inaSampleRateHz = 0;
  double windowS = 0;                       // the rate window length
  std::uint64_t adsEdges = 0;               // ALERT/RDY edges serviced (ready-edge pacing)
  double edgeIoP99Us = 0, edgeIoMaxUs = 0;  // I2C time per edge
};

class LoopStats {
 public:
  // Wall-clock lateness of a wake-up against its deadline.
  void onPeriodError(TimeNs lateness) noexcept;
  void onIo(TimeNs dt) noexcept { io_.add(dt); }
  void onCompute(TimeNs dt) noexcept { compute_.add(dt); }
  void onTick() noexcept { ++ticks_; }
  void onTickCpu(TimeNs dt) noexcept { tickCpu_.add(dt); }
  // own: the tick before the missed deadlines took longer than a period.
  void onOverrun(std::uint64_t missed, bool own = false) noexcept {
    overruns_ += missed;
    if (own) overrunsOwn_ += missed;
  }
  // New samples seen this tick (per ADS channel: how many results arrived;
  // with ready-edge pacing a tick may bring two); rates are computed over 1 s
  // windows of loop time (virtual time in simulation).
  void onSamples(TimeNs now, const std::array<std::uint32_t, 4>& adsNew, bool inaFresh) noexcept;
  // The same from cumulative per-channel counts (results since start, as
  // FastSensors::sampleCounts reports them): the window's count is the
  // difference at its ends, so nothing is summed per tick. Do not mix with
  // onSamples() on one LoopStats.
  // Inline: per tick it is a count and a compare; the window roll (once a
  // second) is out of line.
  void onSampleTotals(TimeNs now, const std::array<std::uint32_t, 4>& adsTotals, bool inaFresh) noexcept {
    if (windowStart_ < 0) windowStart_ = now;
    inaCount_ += inaFresh ? 1 : 0;
    if (now - windowStart_ >= kRateWindow) rollWindow(now, adsTotals);
  }
  // An ADS1115 ready edge serviced between ticks, and (when timed) the I/O
  // time it took.
  void onEdge() noexcept { ++edges_; }
  void onEdgeIo(TimeNs io) noexcept { edgeIo_.add(io); }

  LoopStatsSummary summary() const noexcept;

 private:
  static constexpr TimeNs kRateWindow = 1'000'000'000;
  void rollWindow(TimeNs now, const std::array<std::uint32_t, 4>& adsTotals) noexcept;

  LatencyHistogram periodErr_, compute_, io_, edgeIo_, tickCpu_;
  std::uint64_t ticks_ = 0, overruns_ = 0, overrunsOwn_ = 0, edges_ = 0;
  bool periodMeasured_ = false;
  TimeNs windowStart_ = -1;
  std::array<std::uint32_t, 4> adsTotals_{};  // onSamples(): its running totals
  std::array<std::uint32_t, 4> adsBase_{};    // totals when the window started
  std::uint32_t inaCount_ = 0;
  std::array<double, 4> adsRate_{};
  double inaRate_ = 0, windowS_ = 0;
};

}  // namespace xr::rt
