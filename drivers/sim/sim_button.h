#pragma once
// The simulated pairing button ([pairing] button_line in --sim): a scenario's
// `pairing_button = "pressed" | "released"` events move it on the simulator's
// thread, stamped with simulated time; the daemon's supervisor takes the edges
// from its own thread, as it does from the board's GPIO line.
#include <algorithm>
#include <deque>
#include <mutex>

#include "drivers/hal/button.h"

namespace xr::sim {

class SimButtonInput final : public ButtonInput {
 public:
  // A level change at t (a repeat of the current level is no edge).
  void setPressed(bool pressed, TimeNs t) {
    std::lock_guard lock(m_);
    if (pressed == level_) return;
    level_ = pressed;
    if (edges_.size() >= kMaxQueued) edges_.pop_front();  // nobody reads: keep the newest
    edges_.push_back({pressed, t});
  }
  int takeEdges(std::span<ButtonEdge> out) noexcept override {
    std::lock_guard lock(m_);
    const auto n = std::min(out.size(), edges_.size());
    std::copy_n(edges_.begin(), n, out.begin());
    edges_.erase(edges_.begin(), edges_.begin() + static_cast<std::ptrdiff_t>(n));
    return static_cast<int>(n);
  }

 private:
  static constexpr std::size_t kMaxQueued = 64;
  std::mutex m_;
  bool level_ = false;
  std::deque<ButtonEdge> edges_;
};

}  // namespace xr::sim
