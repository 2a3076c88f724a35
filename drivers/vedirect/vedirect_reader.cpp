#include "drivers/vedirect/vedirect_reader.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <ctime>

namespace xr {

namespace {
TimeNs monotonicNow() {
  timespec ts;
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<TimeNs>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}
}  // namespace

int configureVeDirectTty(int fd) noexcept {
  termios t{};
  if (::tcgetattr(fd, &t) != 0) return errno;
  ::cfmakeraw(&t);
  // 19200 8N1, receiver on, modem lines ignored, no flow control.
  t.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS);
  t.c_cflag |= CS8 | CREAD | CLOCAL;
  t.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  t.c_cc[VMIN] = 0;
  t.c_cc[VTIME] = 0;
  if (::cfsetispeed(&t, B19200) != 0 || ::cfsetospeed(&t, B19200) != 0) return errno;
  if (::tcsetattr(fd, TCSANOW, &t) != 0) return errno;
  return 0;
}

VeDirectReader::VeDirectReader(std::string port, NowFn now, TimeNs reopenPeriod)
    : port_(std::move(port)), now_(std::move(now)), reopenPeriod_(reopenPeriod) {
  if (!now_) now_ = monotonicNow;
}

VeDirectReader::~VeDirectReader() { stop(); }

void VeDirectReader::start() {
  if (thread_.joinable()) return;
  if (::pipe2(wakeFd_, O_CLOEXEC | O_NONBLOCK) != 0) wakeFd_[0] = wakeFd_[1] = -1;
  stop_.store(false);
  thread_ = std::thread([this] { run(); });
}

void VeDirectReader::stop() noexcept {
  stop_.store(true);
  if (wakeFd_[1] >= 0) {
    const char c = 1;
    [[maybe_unused]] auto n = ::write(wakeFd_[1], &c, 1);
  }
  if (thread_.joinable()) thread_.join();
  for (int& fd : wakeFd_) {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
}

void VeDirectReader::onFrame(void* ctx, const vedirect::Frame& f) {
  auto* self = static_cast<VeDirectReader*>(ctx);
  VeDirectSample& s = self->state_;
  // A block without a label keeps the previous value of that label.
  if (f.hasI) s.currentA = f.currentA, s.hasCurrent = true;
  if (f.hasV) s.voltageV = f.voltageV, s.hasVoltage = true;
  if (f.hasPPV) s.ppvW = f.ppvW, s.hasPpv = true;
  s.stamp = self->now_();
  ++s.frames;
}

void VeDirectReader::run() {
  int fd = -1;
  TimeNs nextOpen = 0;
  char buf[256];
  while (!stop_.load()) {
    if (fd < 0) {
      if (now_() >= nextOpen) {
        fd = ::open(port_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
        if (fd >= 0 && configureVeDirectTty(fd) != 0) {
          ::close(fd);
          fd = -1;
        }
        nextOpen = now_() + reopenPeriod_;
        parser_.reset();
        state_.portOpen = fd >= 0;
        out_.store(state_);
      }
      if (fd < 0) {
        pollfd w{wakeFd_[0], POLLIN, 0};
        ::poll(&w, wakeFd_[0] >= 0 ? 1 : 0, 100);
        continue;
      }
    }
    pollfd fds[2] = {{fd, POLLIN, 0}, {wakeFd_[0], POLLIN, 0}};
    const int n = ::poll(fds, wakeFd_[0] >= 0 ? 2 : 1, 500);
    if (n < 0 && errno == EINTR) continue;
    bool lost = n < 0;
    if (n > 0 && (fds[0].revents & POLLIN)) {
      const ssize_t r = ::read(fd, buf, sizeof(buf));
      if (r > 0) {
        const std::uint32_t framesBefore = state_.frames;
        parser_.feed(std::string_view(buf, static_cast<std::size_t>(r)), &VeDirectReader::onFrame, this);
        state_.badChecksums = parser_.badChecksums();
        out_.store(state_);
        if (sink_ && state_.frames != framesBefore) sink_(state_);
      } else if (r == 0 || (errno != EAGAIN && errno != EINTR)) {
        lost = true;
      }
    } else if (n > 0 && (fds[0].revents & (POLLHUP | POLLERR | POLLNVAL))) {
      lost = true;
    }
    if (lost) {
      // Unplugged (USB adapter gone) or hung up: close and retry later.
      ::close(fd);
      fd = -1;
      nextOpen = now_() + reopenPeriod_;
      state_.portOpen = false;
      out_.store(state_);
    }
  }
  if (fd >= 0) ::close(fd);
}

}  // namespace xr
