#include "drivers/gpio/gpio_button.h"

#include <gpiod.h>

#include <cerrno>
#include <cstring>
#include <ctime>

#include "drivers/gpio/gpio_libgpiod.h"

namespace xr {

GpioButtonLine::~GpioButtonLine() { close(); }

void GpioButtonLine::close() noexcept {
  if (line_) gpiod_line_release(line_);
  line_ = nullptr;
  if (chip_) gpiod_chip_close(chip_);
  chip_ = nullptr;
}

bool GpioButtonLine::open(const std::string& chipName, int line) {
  close();
  error_.clear();
  chip_ = gpiod_chip_open_lookup(chipName.c_str());
  if (!chip_) {
    error_ = "gpio: cannot open " + chipName + " for the pairing button: " + std::strerror(errno);
    return false;
  }
  line_ = gpiod_chip_get_line(chip_, static_cast<unsigned>(line));
  // Active low with the pull-up: "pressed" is the line pulled to GND.
  const int flags = GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW | GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
  if (!line_ || gpiod_line_request_both_edges_events_flags(line_, kGpioConsumer, flags) != 0) {
    error_ = "gpio: cannot request the pairing button (line " + std::to_string(line) + " on " + chipName +
             "): " + std::strerror(errno) + " (is another program using it? see 'gpioinfo')";
    line_ = nullptr;
    close();
    return false;
  }
  return true;
}

int GpioButtonLine::takeEdges(std::span<ButtonEdge> out) noexcept {
  if (!line_) return -1;
  int n = 0;
  while (n < static_cast<int>(out.size())) {
    timespec none{0, 0};
    const int rc = gpiod_line_event_wait(line_, &none);  // never blocks: only what is queued
    if (rc < 0) return -1;
    if (rc == 0) break;
    gpiod_line_event ev;
    if (gpiod_line_event_read(line_, &ev) != 0) return -1;
    // ACTIVE_LOW: libgpiod reports the logical edge, "rising" = pressed.
    out[n].pressed = ev.event_type == GPIOD_LINE_EVENT_RISING_EDGE;
    out[n].at = static_cast<TimeNs>(ev.ts.tv_sec) * 1'000'000'000LL + ev.ts.tv_nsec;
    ++n;
  }
  return n;
}

}  // namespace xr
