#pragma once
// The one byte-level seam every I2C chip driver talks through. The Linux
// implementation issues a single I2C_RDWR ioctl per transfer(); the simulated
// bus dispatches the same messages to register-level chip models.
#include <cstddef>
#include <cstdint>
#include <span>

namespace xr {

struct I2cMsg {
  std::uint16_t addr = 0;
  bool read = false;            // false = write
  std::uint8_t* buf = nullptr;  // for writes, the bytes to send
  std::size_t len = 0;
};

class I2cBus {
 public:
  virtual ~I2cBus() = default;
  // Runs the messages as one combined transaction (repeated start between
  // messages). Returns 0 on success or a positive errno (EREMOTEIO / ENXIO for
  // a NACK, ETIMEDOUT, EIO, ...). Never throws: it is called on the RT path.
  virtual int transfer(std::span<I2cMsg> msgs) noexcept = 0;
};

}  // namespace xr
