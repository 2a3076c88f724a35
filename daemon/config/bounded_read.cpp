#include "config/bounded_read.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace xr {

namespace {

const char* kindOf(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISFIFO(m)) return "a FIFO (named pipe)";
  if (S_ISSOCK(m)) return "a socket";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  return "not a regular file";
}

struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string readConfigText(const std::string& path, std::string& text, std::size_t maxBytes) {
  // O_NONBLOCK: opening a FIFO without a writer would otherwise block here
  // (with the stop signals already blocked by main). It has no effect on the
  // read of a regular file.
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY)};
  if (f.fd < 0) return std::string("cannot read the file: ") + std::strerror(errno);
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) return std::string("cannot read the file: ") + std::strerror(errno);
  if (!S_ISREG(st.st_mode)) return std::string("is ") + kindOf(st.st_mode) + ", not a configuration file";
  if (static_cast<std::size_t>(st.st_size) > maxBytes)
    return "is " + std::to_string(st.st_size) + " bytes; a configuration file is at most " +
           std::to_string(maxBytes) + " bytes";
  // The size is checked again while reading: the file may grow after fstat.
  text.clear();
  char buf[16384];
  while (true) {
    const ssize_t n = ::read(f.fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      return std::string("cannot read the file: ") + std::strerror(errno);
    }
    if (n == 0) break;
    if (text.size() + static_cast<std::size_t>(n) > maxBytes)
      return "grew beyond " + std::to_string(maxBytes) + " bytes while being read";
    text.append(buf, static_cast<std::size_t>(n));
  }
  return {};
}

}  // namespace xr
