#include "drivers/gpio/gpio_libgpiod.h"

#include <gpiod.h>

#include <cerrno>
#include <cstring>
#include <ctime>

namespace xr {

namespace {
gpiod_chip* openChip(const std::string& name) {
  // Accepts "gpiochip0", "/dev/gpiochip0", a label or a number.
  return gpiod_chip_open_lookup(name.c_str());
}
std::string chipHint(const std::string& name, int e) {
  std::string s = "gpio: cannot open " + name + ": " + std::strerror(e);
  if (e == EACCES) s += " (add the service user to the 'gpio' group)";
  if (e == ENOENT) s += " (no such gpiochip; check [hardware] gpio_chip and 'gpiodetect')";
  return s;
}
}  // namespace

GpioOutputLine::~GpioOutputLine() {
  if (line_) gpiod_line_release(line_);
}
bool GpioOutputLine::set(bool on) noexcept {
  return line_ && gpiod_line_set_value(line_, physicalLevel(on, activeHigh_)) == 0;
}

void GpioOutputLine::setOffSignalSafe(void* self) noexcept {
  auto* l = static_cast<GpioOutputLine*>(self);
  if (l && l->line_) gpiod_line_set_value(l->line_, physicalLevel(false, l->activeHigh_));
}

GpioInputLine::~GpioInputLine() {
  if (line_) gpiod_line_release(line_);
}
int GpioInputLine::get() noexcept {
  if (!line_) return -1;
  return logicalLevel(gpiod_line_get_value(line_), activeLow_);
}

GpioLibgpiod::~GpioLibgpiod() { close(); }

void GpioLibgpiod::close() noexcept {
  // Field enable LOW before release: a released line may float.
  if (fieldEnable_) fieldEnable_->set(false);
  fieldEnable_.reset();
  buzzer_.reset();
  bms_.reset();
  ignition_.reset();
  if (chip_) gpiod_chip_close(chip_);
  chip_ = nullptr;
}

bool GpioLibgpiod::open(const HardwareSettings& hw) {
  close();
  error_.clear();
  chip_ = openChip(hw.gpio_chip);
  if (!chip_) {
    error_ = chipHint(hw.gpio_chip, errno);
    return false;
  }
  auto requestOut = [&](int offset, int initialPhysical, const char* what) -> gpiod_line* {
    gpiod_line* l = gpiod_chip_get_line(chip_, static_cast<unsigned>(offset));
    if (!l || gpiod_line_request_output(l, kGpioConsumer, initialPhysical) != 0) {
      error_ = std::string("gpio: cannot request ") + what + " (line " + std::to_string(offset) + " on " +
               hw.gpio_chip + "): " + std::strerror(errno) + " (is another program using it? see 'gpioinfo')";
      return nullptr;
    }
    return l;
  };
  auto requestIn = [&](int offset, const char* what) -> gpiod_line* {
    gpiod_line* l = gpiod_chip_get_line(chip_, static_cast<unsigned>(offset));
    if (!l || gpiod_line_request_input(l, kGpioConsumer) != 0) {
      error_ = std::string("gpio: cannot request ") + what + " (line " + std::to_string(offset) + " on " +
               hw.gpio_chip + "): " + std::strerror(errno);
      return nullptr;
    }
    return l;
  };
  // Field enable first, requested with its OFF level so the field never
  // pulses on at start.
  gpiod_line* fe =
      requestOut(hw.field_enable_line, physicalLevel(false, hw.field_enable_active_high), "field enable");
  if (!fe) {
    close();
    return false;
  }
  fieldEnable_ = std::make_unique<GpioOutputLine>(fe, hw.field_enable_active_high);
  if (hw.buzzer_line >= 0) {
    gpiod_line* bz = requestOut(hw.buzzer_line, 0, "buzzer");
    if (!bz) {
      close();
      return false;
    }
    buzzer_ = std::make_unique<GpioOutputLine>(bz, true);
  }
  if (hw.bms_line >= 0) {
    gpiod_line* l = requestIn(hw.bms_line, "BMS input");
    if (!l) {
      close();
      return false;
    }
    // bms_active_low describes the level meaning "charge disabled"; the
    // DigitalInput reports logical "charge disabled asserted".
    bms_ = std::make_unique<GpioInputLine>(l, hw.bms_active_low);
  }
  if (hw.ignition_line >= 0) {
    gpiod_line* l = requestIn(hw.ignition_line, "ignition input");
    if (!l) {
      close();
      return false;
    }
    ignition_ = std::make_unique<GpioInputLine>(l, hw.ignition_active_low);
  }
  return true;
}

AdsReadyLine::~AdsReadyLine() { close(); }

void AdsReadyLine::close() noexcept {
  if (line_) gpiod_line_release(line_);
  line_ = nullptr;
  if (chip_) gpiod_chip_close(chip_);
  chip_ = nullptr;
}

bool AdsReadyLine::open(const std::string& chipName, int line) {
  close();
  error_.clear();
  chip_ = openChip(chipName);
  if (!chip_) {
    error_ = chipHint(chipName, errno);
    return false;
  }
  line_ = gpiod_chip_get_line(chip_, static_cast<unsigned>(line));
  // ALERT/RDY is open drain, active low by default (COMP_POL=0): falling edges.
  if (!line_ || gpiod_line_request_falling_edge_events(line_, kGpioConsumer) != 0) {
    error_ =
        "gpio: cannot request ADS1115 ALERT/RDY (line " + std::to_string(line) + "): " + std::strerror(errno);
    line_ = nullptr;
    close();
    return false;
  }
  return true;
}

int AdsReadyLine::fd() const noexcept { return line_ ? gpiod_line_event_get_fd(line_) : -1; }

int AdsReadyLine::wait(long timeoutNs, long long* stampNs) noexcept {
  if (!line_) return -1;
  timespec to{timeoutNs / 1'000'000'000, timeoutNs % 1'000'000'000};
  const int rc = gpiod_line_event_wait(line_, &to);
  if (rc <= 0) return rc;
  gpiod_line_event ev;
  if (gpiod_line_event_read(line_, &ev) != 0) return -1;
  if (stampNs) *stampNs = static_cast<long long>(ev.ts.tv_sec) * 1'000'000'000LL + ev.ts.tv_nsec;
  return 1;
}

}  // namespace xr
