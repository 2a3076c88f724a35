#include "drivers/onewire/ds18b20_reader.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
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

Ds18b20Reader::~Ds18b20Reader() {
  stop();
  closeSlave();
}

void Ds18b20Reader::closeSlave() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

long Ds18b20Reader::readSlave(int fd, char* buf, std::size_t cap) noexcept {
  // w1_slave is two lines; the kernel hands both over in one read, so the
  // loop normally runs once (a short read would be continued from its end).
  std::size_t len = 0;
  int lines = 0;
  while (len < cap && lines < 2) {
    const ssize_t n = ::pread(fd, buf + len, cap - len, off_t(len));
    if (n < 0) {
      if (errno == EINTR) continue;
      return -1;
    }
    if (n == 0) break;
    for (ssize_t i = 0; i < n; ++i) lines += buf[len + std::size_t(i)] == '\n';
    len += std::size_t(n);
  }
  return long(len);
}

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
      for (const auto& found : w1::listDs18b20(root_)) {
        if (found == exclude_) continue;
        id = found;
        break;
      }
    }
    if (!id.empty()) path_ = root_ + "/" + id + "/w1_slave";
  }
  w1::W1Reading r;
  r.error = w1::ParseError::Empty;
  if (!path_.empty()) {
    // A read triggers the conversion (~750 ms at 12 bits): this is why it
    // lives on its own thread, never on the control thread.
    // The file stays open between readings: a sysfs attribute runs its show()
    // (here the conversion) again on every read from offset 0, so one pread
    // replaces open/read/close and the path lookup. Once the slave is gone its
    // attribute fails to read (ENODEV) or reads empty; then the path is opened
    // afresh, which also finds a sensor that came back.
    char buf[256];
    long len = fd_ >= 0 ? readSlave(fd_, buf, sizeof buf) : -1;
    if (len <= 0) {
      closeSlave();
      fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
      if (fd_ >= 0) len = readSlave(fd_, buf, sizeof buf);
    }
    if (fd_ >= 0) {
      r = w1::parseW1Slave(std::string_view(buf, len > 0 ? std::size_t(len) : 0));
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
  out_.store(state_);
  if (sink_) sink_(state_);
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
