#include "runtime/output_mirror.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "runtime/fatal_guard.h"

namespace xr::rt {

namespace {
// snprintf into a fixed buffer: no allocation, fine on the RT thread.
void fillLine(char* buf, double duty, bool enable, bool buzzer, const char* via) {
  char tmp[OutputMirror::kLineLen * 2];
  int n = std::snprintf(tmp, sizeof(tmp), "duty_pct=%7.3f enable=%d buzzer=%d via=%s", duty, enable ? 1 : 0,
                        buzzer ? 1 : 0, via);
  if (n < 0) n = 0;
  const std::size_t len = std::min<std::size_t>(static_cast<std::size_t>(n), OutputMirror::kLineLen - 1);
  std::memset(buf, ' ', OutputMirror::kLineLen);
  std::memcpy(buf, tmp, len);
  buf[OutputMirror::kLineLen - 1] = '\n';
}
}  // namespace

OutputMirror::OutputMirror(const std::string& path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot open sim outputs file " + path + ": " + std::strerror(errno));
  fillLine(fatalLine_, 0.0, false, false, "fatal");
  write("run");
}

OutputMirror::~OutputMirror() {
  if (fd_ >= 0) ::close(fd_);
}

std::string OutputMirror::formatLine(double duty, bool enable, bool buzzer, const char* via) {
  char buf[kLineLen];
  fillLine(buf, duty, enable, buzzer, via);
  return std::string(buf, kLineLen);
}

void OutputMirror::write(const char* via) noexcept {
  char buf[kLineLen];
  fillLine(buf, duty_.load(), enable_.load(), buzzer_.load(), via);
  [[maybe_unused]] auto n = ::pwrite(fd_, buf, kLineLen, 0);
}

void OutputMirror::setDuty(double pct) noexcept {
  if (duty_.exchange(pct) != pct) write("run");
}
void OutputMirror::setEnable(bool on) noexcept {
  if (enable_.exchange(on) != on) write("run");
}
void OutputMirror::setBuzzer(bool on) noexcept {
  if (buzzer_.exchange(on) != on) write("run");
}
void OutputMirror::markStopped() noexcept { write("stop"); }

void OutputMirror::registerFatalAction() { fatal::addWrite(fd_, fatalLine_, kLineLen, 0); }

}  // namespace xr::rt
