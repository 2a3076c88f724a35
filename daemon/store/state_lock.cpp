#include "store/state_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace xr {

namespace {
std::string readHolder(int fd) {
  char buf[32] = {};
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  std::string s(buf, n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s.empty() ? "unknown" : s;
}
}  // namespace

std::string StateLock::resolvedPath(const std::string& databasePath) {
  // Every symlink on the way resolved (the file's own too, when it exists):
  // "dlink.db -> d.db" and "/data -> /mnt/sd/data" name the same file, so
  // they must name the same lock.
  std::error_code ec;
  const auto p = std::filesystem::weakly_canonical(std::filesystem::absolute(databasePath, ec), ec);
  return ec || p.empty() ? databasePath : p.string();
}

StateLock::StateLock(const std::string& databasePath) : path_(resolvedPath(databasePath) + ".lock") {
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    message_ = "cannot create the lock file " + path_ + ": " + std::strerror(errno);
    return;
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    if (err == EWOULDBLOCK) {
      result_ = Result::HeldByOther;
      const std::string real = resolvedPath(databasePath);
      message_ = "another xregulatord (pid " + readHolder(fd_) + ") uses the state database " + databasePath +
                 (real != databasePath ? " (the file " + real + ")" : std::string()) +
                 "; one daemon per state database";
    } else {
      message_ = "cannot lock " + path_ + ": " + std::strerror(err);  // no flock on this file system
    }
    ::close(fd_);
    fd_ = -1;
    return;
  }
  result_ = Result::Held;
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) == 0 &&
      ::pwrite(fd_, pid.data(), pid.size(), 0) == static_cast<ssize_t>(pid.size()))
    message_ = "locked " + path_;
  else
    message_ = "locked " + path_ + " (the pid could not be written)";
}

StateLock::~StateLock() {
  if (fd_ >= 0) ::close(fd_);  // closing drops the flock
}

}  // namespace xr
