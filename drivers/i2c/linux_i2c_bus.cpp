#include "drivers/i2c/linux_i2c_bus.h"

#include <fcntl.h>
#include <linux/i2c-dev.h>
#include <linux/i2c.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>

namespace xr {

bool isTransientI2cError(int err) noexcept {
  // A NACK (EREMOTEIO/ENXIO on most adapters) is retried too: a chip may NACK
  // once while busy (INA228 in its power-on window); an absent chip NACKs
  // every attempt and the bounded retries keep that cheap.
  return err == EAGAIN || err == ETIMEDOUT || err == EIO || err == EREMOTEIO || err == ENXIO || err == EINTR;
}

LinuxI2cBus::~LinuxI2cBus() { close(); }

int LinuxI2cBus::open(const std::string& path) noexcept {
  close();
  path_ = path;
  const int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return errno;
  // Reject files that are not i2c-dev adapters up front (I2C_FUNCS is a
  // harmless query every adapter answers).
  unsigned long funcs = 0;
  if (::ioctl(fd, I2C_FUNCS, &funcs) < 0) {
    const int err = errno;
    ::close(fd);
    return err;
  }
  if ((funcs & I2C_FUNC_I2C) == 0) {
    ::close(fd);
    return EOPNOTSUPP;  // SMBus-only adapter: no combined I2C_RDWR transactions
  }
  fd_ = fd;
  return 0;
}

void LinuxI2cBus::close() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

int LinuxI2cBus::transfer(std::span<I2cMsg> msgs) noexcept {
  if (fd_ < 0) return EBADF;
  if (msgs.empty() || msgs.size() > static_cast<std::size_t>(kMaxMsgs)) return EINVAL;
  i2c_msg km[kMaxMsgs];
  for (std::size_t i = 0; i < msgs.size(); ++i) {
    if (msgs[i].len > 0xFFFF || (msgs[i].len > 0 && msgs[i].buf == nullptr)) return EINVAL;
    km[i].addr = msgs[i].addr;
    km[i].flags = msgs[i].read ? I2C_M_RD : 0;
    km[i].len = static_cast<__u16>(msgs[i].len);
    km[i].buf = msgs[i].buf;
  }
  i2c_rdwr_ioctl_data data{km, static_cast<__u32>(msgs.size())};
  ++transfers_;
  int err = 0;
  for (int attempt = 0; attempt <= retries_; ++attempt) {
    if (attempt > 0) ++retriesUsed_;
    if (::ioctl(fd_, I2C_RDWR, &data) >= 0) return 0;
    err = errno;
    if (!isTransientI2cError(err)) break;
  }
  ++failures_;
  return err;
}

}  // namespace xr
