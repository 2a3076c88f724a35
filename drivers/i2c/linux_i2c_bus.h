#pragma once
// LinuxI2cBus: the I2cBus seam on /dev/i2c-N (docs/install.md, wiring). One I2C_RDWR
// ioctl per transfer() (a combined transaction with repeated starts), a
// bounded number of retries for transient errors, errno returned as a value.
// RT-safe: transfer() does not allocate, throw or lock.
#include <string>

#include "drivers/hal/i2c_bus.h"

namespace xr {

class LinuxI2cBus final : public I2cBus {
 public:
  static constexpr int kMaxMsgs = 8;  // messages per combined transaction
  // `retries`: extra attempts after a transient failure (EAGAIN, ETIMEDOUT,
  // EIO, EREMOTEIO). Kept small: the control tick is 2.5 ms.
  explicit LinuxI2cBus(int retries = 2) noexcept : retries_(retries) {}
  ~LinuxI2cBus() override;
  LinuxI2cBus(const LinuxI2cBus&) = delete;
  LinuxI2cBus& operator=(const LinuxI2cBus&) = delete;

  // Opens the device (e.g. "/dev/i2c-1"). Returns 0 or errno. Not RT (open()).
  int open(const std::string& path) noexcept;
  void close() noexcept;
  // Takes ownership of an already open descriptor without the adapter
  // check (tests drive the ioctl error path with a non-i2c fd this way).
  void adoptFd(int fd) noexcept {
    close();
    fd_ = fd;
  }
  bool isOpen() const noexcept { return fd_ >= 0; }
  const std::string& path() const noexcept { return path_; }

  // 0 or a positive errno. EBADF when not open, EINVAL for an empty or
  // oversized message list.
  int transfer(std::span<I2cMsg> msgs) noexcept override;

  // Counters for telemetry/--probe (written by the transfer() caller thread only).
  unsigned long transfers() const noexcept { return transfers_; }
  unsigned long failures() const noexcept { return failures_; }
  unsigned long retriesUsed() const noexcept { return retriesUsed_; }

 private:
  int fd_ = -1;
  int retries_;
  std::string path_;
  unsigned long transfers_ = 0;
  unsigned long failures_ = 0;
  unsigned long retriesUsed_ = 0;
};

// True for errors worth retrying within the same tick.
bool isTransientI2cError(int err) noexcept;

}  // namespace xr
