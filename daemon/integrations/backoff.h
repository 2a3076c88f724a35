#pragma once
// Exponential reconnect backoff (docs/integrations.md): 1 s, 2 s, 4 s ... up to a cap, back
// to the start after a good connection. Pure: the caller owns the timer.
#include <algorithm>
#include <chrono>

namespace xr::integrations {

class Backoff {
 public:
  using ms = std::chrono::milliseconds;
  explicit Backoff(ms first = ms(1000), ms cap = ms(30000)) : first_(first), cap_(cap), next_(first) {}

  // The delay before the next attempt; each call doubles the one after.
  ms next() {
    const ms d = next_;
    next_ = std::min(cap_, next_ * 2);
    return d;
  }
  void reset() { next_ = first_; }

 private:
  ms first_, cap_, next_;
};

}  // namespace xr::integrations
