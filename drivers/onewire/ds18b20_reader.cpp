#include "drivers/onewire/ds18b20_reader.h"

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <ctime>

namespace xr {

namespace {
TimeNs monotonicNow() {
  timespec ts;
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<TimeNs>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}
}  // namespace

Ds18b20Reader::Ds18b20Reader(std::string root, std::string sensorId, TimeNs period, NowFn now)
    : root_(std::move(root)), id_(std::move(sensorId)), period_(period), now_(std::move(now)) {
  if (!now_) now_ = monotonicNow;
}

Ds18b20Reader::~Ds18b20Reader() { stop(); }

void Ds18b20Reader::start() {
  if (thread_.joinable()) return;
  stop_.store(false);
  thread_ = std::thread([this] { run(); });
}

void Ds18b20Reader::stop() noexcept {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void Ds18b20Reader::readOnce() {
  if (path_.empty()) {
    std::string id = id_;
    if (id.empty()) {
      const auto all = w1::listDs18b20(root_);
      if (!all.empty()) id = all.front();
    }
    if (!id.empty()) path_ = root_ + "/" + id + "/w1_slave";
  }
  w1::W1Reading r;
  r.error = w1::ParseError::Empty;
  if (!path_.empty()) {
    // A read triggers the conversion (~750 ms at 12 bits): this is why it
    // lives on its own thread, never on the control thread.
    const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
      char buf[256];
      std::size_t len = 0;
      for (;;) {
        const ssize_t n = ::read(fd, buf + len, sizeof(buf) - 1 - len);
        if (n <= 0) break;
        len += static_cast<std::size_t>(n);
        if (len >= sizeof(buf) - 1) break;
      }
      ::close(fd);
      r = w1::parseW1Slave(std::string_view(buf, len));
      state_.sensorFound = true;
    } else {
      state_.sensorFound = false;
      if (id_.empty()) path_.clear();  // rescan: a different sensor may be plugged in
    }
  } else {
    state_.sensorFound = false;
  }
  const TimeNs t = now_();
  if (r.error == w1::ParseError::None) {
    state_.tempF = r.milliC / 1000.0 * 9.0 / 5.0 + 32.0;
    state_.stamp = t;
    ++state_.good;
  } else {
    ++state_.bad;
  }
  state_.lastError = r.error;
  state_.heartbeat = t;
  out_.publish(state_);
}

void Ds18b20Reader::run() {
  while (!stop_.load()) {
    const TimeNs t0 = now_();
    readOnce();
    // Sleep in small slices so stop() returns promptly.
    while (!stop_.load() && now_() - t0 < period_) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace xr
