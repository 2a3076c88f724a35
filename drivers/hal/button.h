#pragma once
// A push button read by its edges (docs/security.md "Pairing without a
// terminal": the pairing button). Polled from a non-RT thread; the edges keep
// their own time stamps, so a press shorter than the polling period is still
// seen with its true length, and a contact's bounce can be told from a press.
#include <cstdint>
#include <span>

#include "core/time.h"

namespace xr {

struct ButtonEdge {
  bool pressed = false;  // true: the button went down; false: it was let go
  TimeNs at = 0;         // on the loop's clock (CLOCK_MONOTONIC on the board, simulated time in --sim)
};

class ButtonInput {
 public:
  virtual ~ButtonInput() = default;
  // The edges since the last call, oldest first, at most out.size() of them
  // (the rest wait for the next call). -1 on a read error.
  virtual int takeEdges(std::span<ButtonEdge> out) noexcept = 0;
};

}  // namespace xr
