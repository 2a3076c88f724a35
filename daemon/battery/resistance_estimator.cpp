// ResistanceEstimator (docs/batteries.md "Internal resistance").
#include "battery/resistance_estimator.h"

#include <algorithm>
#include <cmath>

namespace xr {

using namespace resistance_k;

namespace {
struct Level {
  double mean = 0.0;
  bool steady = false;
};
// The mean of n one-second values and whether each is within the band of it.
template <typename At>
Level levelOf(At at, int from, int n) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += at(from + i);
  Level l{sum / n, true};
  const double band = std::max(kSteadyA, kSteadyShare * std::fabs(l.mean));
  for (int i = 0; i < n; ++i)
    if (std::fabs(at(from + i) - l.mean) > band) l.steady = false;
  return l;
}
}  // namespace

double ResistanceEstimator::temperatureFactor(double tempC) noexcept {
  if (!std::isfinite(tempC)) return 1.0;
  return std::exp(kArrheniusB * (1.0 / (tempC + 273.15) - 1.0 / 298.15));
}

bool ResistanceEstimator::update(double dt_s, double amps, double volts, double tempC,
                                 double capacityAh) noexcept {
  if (!(dt_s > 0.0)) return false;
  if (!std::isfinite(amps) || !std::isfinite(volts)) gap_ = true;
  accA_ += std::isfinite(amps) ? amps * dt_s : 0.0;
  accV_ += std::isfinite(volts) ? volts * dt_s : 0.0;
  accT_ += dt_s;
  if (accT_ < 1.0 - 1e-6) return false;  // a second of ticks, whatever their rounding
  return closeSecond(tempC, capacityAh);
}

bool ResistanceEstimator::closeSecond(double tempC, double capacityAh) noexcept {
  const double a = accA_ / accT_, v = accV_ / accT_;
  const bool gap = gap_;
  accA_ = accV_ = accT_ = 0.0;
  gap_ = false;
  if (gap) {
    filled_ = 0;  // a window with a hole in it is not measured
    return false;
  }
  sinceCharge_s_ = a > kMaxChargeA ? 0.0 : sinceCharge_s_ + 1.0;
  const int tail = (head_ + filled_) % kWindowS;
  secA_[tail] = a;
  secV_[tail] = v;
  if (filled_ < kWindowS)
    ++filled_;
  else
    head_ = (head_ + 1) % kWindowS;
  if (filled_ < kWindowS || sinceCharge_s_ < kWindowS + kAfterChargeS) return false;
  double r = 0.0;
  if (!detectStep(r, capacityAh)) return false;
  filled_ = 0;  // one step, one sample: the seconds around it would match again
  r /= temperatureFactor(tempC);
  if (!(r >= kMinMohm && r <= kMaxMohm)) return false;
  push(r);
  return true;
}

// The window holds kBeforeS seconds before the step, the step's kSkipS
// seconds, then the hold; the step is judged once, when it is exactly there.
bool ResistanceEstimator::detectStep(double& rMohm, double capacityAh) const noexcept {
  auto amps = [&](int i) { return secA_[(head_ + i) % kWindowS]; };
  auto volts = [&](int i) { return secV_[(head_ + i) % kWindowS]; };
  const Level before = levelOf(amps, 0, kBeforeS);
  const Level after = levelOf(amps, kBeforeS + kSkipS, kAfterS - kSkipS);
  if (!before.steady || !after.steady) return false;
  if (before.mean > kMaxChargeA || after.mean > kMaxChargeA) return false;
  const double step = after.mean - before.mean;
  const double minStep = std::max(kMinStepA, kMinStepC * (std::isfinite(capacityAh) ? capacityAh : 0.0));
  if (std::fabs(step) < minStep) return false;
  const int from = kWindowS - kMeasureS;
  const Level measuredA = levelOf(amps, from, kMeasureS);
  const Level vBefore = levelOf(volts, 0, kBeforeS);
  const Level vAfter = levelOf(volts, from, kMeasureS);
  rMohm = (vAfter.mean - vBefore.mean) / (measuredA.mean - before.mean) * 1000.0;
  return std::isfinite(rMohm);
}

void ResistanceEstimator::push(double rMohm) noexcept {
  int next = static_cast<int>(l_.next);
  if (next < 0 || next >= kResistanceSamples) next = 0;
  l_.samples_mohm[next] = rMohm;
  l_.next = (next + 1) % kResistanceSamples;
  l_.count = std::min<double>(kResistanceSamples, l_.count + 1.0);
}

double ResistanceEstimator::medianMohm() const noexcept {
  const int n = samples();
  if (n < kMinSamples) return std::nan("");
  std::array<double, kResistanceSamples> s{};
  std::copy_n(l_.samples_mohm.begin(), n, s.begin());
  std::sort(s.begin(), s.begin() + n);
  return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

double ResistanceEstimator::spreadMohm() const noexcept {
  const int n = samples();
  if (n < kMinSamples) return std::nan("");
  double mean = 0.0;
  for (int i = 0; i < n; ++i) mean += l_.samples_mohm[i];
  mean /= n;
  double ss = 0.0;
  for (int i = 0; i < n; ++i) ss += (l_.samples_mohm[i] - mean) * (l_.samples_mohm[i] - mean);
  return std::sqrt(ss / (n - 1));
}

double ResistanceEstimator::ohmsAt(double tempC) const noexcept {
  const double m = medianMohm();
  return std::isfinite(m) ? m / 1000.0 * temperatureFactor(std::isfinite(tempC) ? tempC : 25.0)
                          : std::nan("");
}

void ResistanceEstimator::restore(const ResistanceLedger& in) noexcept {
  ResistanceLedger l{};
  const double c = in.count;
  if (!(std::isfinite(c) && c >= 0.0 && c <= kResistanceSamples && std::isfinite(in.next))) {
    l_ = l;
    return;
  }
  // Only plausible samples come back; the ring restarts packed.
  int n = 0;
  for (int i = 0; i < static_cast<int>(c); ++i) {
    const double r = in.samples_mohm[i];
    if (std::isfinite(r) && r >= kMinMohm && r <= kMaxMohm) l.samples_mohm[n++] = r;
  }
  l.count = n;
  const double next = std::floor(in.next);
  l.next =
      n == kResistanceSamples && next >= 0.0 && next < kResistanceSamples ? next : n % kResistanceSamples;
  l_ = l;
}

}  // namespace xr
