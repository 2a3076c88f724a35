#pragma once
// The pairing button on a GPIO line (docs/install.md "Pairing button"): a
// push button between the line and GND, the SoC's internal pull-up holding it
// HIGH when let go; requested active-low with both edges as libgpiod 1.6 line
// events, so each press and release comes with the kernel's time stamp
// (CLOCK_MONOTONIC since Linux 5.7, the loop's clock on the board).
#include <string>

#include "drivers/hal/button.h"

struct gpiod_chip;
struct gpiod_line;

namespace xr {

class GpioButtonLine final : public ButtonInput {
 public:
  GpioButtonLine() = default;
  ~GpioButtonLine() override;
  GpioButtonLine(const GpioButtonLine&) = delete;
  GpioButtonLine& operator=(const GpioButtonLine&) = delete;
  // Not RT. On failure `error()` says what to fix and nothing stays requested.
  bool open(const std::string& chipName, int line);
  const std::string& error() const noexcept { return error_; }
  int takeEdges(std::span<ButtonEdge> out) noexcept override;
  void close() noexcept;

 private:
  gpiod_chip* chip_ = nullptr;
  gpiod_line* line_ = nullptr;
  std::string error_;
};

}  // namespace xr
