#pragma once
// Feedback filters on the CH1 record path (docs/control.md "Feedback
// filters"): an EMA with a time constant in ms (real dt, so the corner does
// not move with the tick rate) and a fixed-capacity moving average.
#include <array>
#include <cmath>
#include <cstddef>

namespace xr {

class Ema {
 public:
  // tcMs <= 0 passes the raw value. The first sample initialises the filter.
  double update(double x, double dtSec, double tcMs) {
    if (!std::isfinite(x)) return value_;
    if (!primed_ || tcMs <= 0.0) {
      value_ = x;
      primed_ = true;
      return value_;
    }
    const double tc = tcMs * 1e-3;
    const double alpha = dtSec > 0.0 ? dtSec / (tc + dtSec) : 0.0;
    value_ += alpha * (x - value_);
    return value_;
  }
  double value() const { return value_; }
  bool primed() const { return primed_; }
  void reset(double v) {
    value_ = v;
    primed_ = true;
  }

 private:
  double value_ = 0.0;   // the filtered value
  bool primed_ = false;  // the first sample has set it
};

template <std::size_t Capacity>
class MovingAverage {
 public:
  // Window n is clamped to [1, Capacity]; changing it restarts the average.
  double update(double x, int n) {
    if (!std::isfinite(x)) return value();
    std::size_t w =
        n < 1 ? 1 : (static_cast<std::size_t>(n) > Capacity ? Capacity : static_cast<std::size_t>(n));
    if (w != window_) {
      window_ = w;
      count_ = head_ = 0;
      sum_ = 0.0;
    }
    if (count_ == window_)
      sum_ -= buf_[(head_ + Capacity - window_) % Capacity];
    else
      ++count_;
    buf_[head_] = x;
    head_ = (head_ + 1) % Capacity;
    sum_ += x;
    return value();
  }
  double value() const { return count_ ? sum_ / static_cast<double>(count_) : 0.0; }

 private:
  std::array<double, Capacity> buf_{};             // the window's samples (a ring)
  std::size_t window_ = 0, count_ = 0, head_ = 0;  // its length, fill and head
  double sum_ = 0.0;                               // the running sum
};

}  // namespace xr
