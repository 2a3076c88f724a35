#pragma once
// A register-level chip model on the simulated I2C bus, in the shape of
// ArduPilot's SITL I2C devices: the messages of a combined transaction are
// handed to the chip as writes and reads, and the chip converts on the
// simulated clock through update(). Return 0 or a positive errno; a chip
// that would not accept what it was sent answers EREMOTEIO (NACK), so a driver
// bug surfaces as an I/O error in tests instead of silently "working".
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/time.h"
#include "drivers/hal/i2c_bus.h"

namespace xr::sim {

class SimI2cDevice {
 public:
  virtual ~SimI2cDevice() = default;
  // Bring the chip's conversions up to simulated time t (monotonic: a time
  // already reached is a no-op).
  virtual void update(TimeNs t) noexcept = 0;
  // One combined transaction addressed to this chip (repeated starts between
  // the messages): the chip is brought up to t, then the messages run in
  // order. A message with len > 0 and no buffer stops the transaction with
  // EFAULT before it reaches the chip, a refused one with its errno; the
  // messages before it took effect, as on the wire.
  int transact(TimeNs t, std::span<I2cMsg> msgs) noexcept {
    update(t);
    for (I2cMsg& m : msgs) {
      if (m.buf == nullptr && m.len > 0) return EFAULT;
      const int rc = m.read ? read(m.buf, m.len) : write(m.buf, m.len);
      if (rc != 0) return rc;
    }
    return 0;
  }
  // One write message (pointer byte, then data bytes MSB first).
  virtual int write(const std::uint8_t* buf, std::size_t len) noexcept = 0;
  // One read message from the retained pointer.
  virtual int read(std::uint8_t* buf, std::size_t len) noexcept = 0;
  // Number of messages the chip refused (driver bugs; tests assert on it).
  std::uint64_t protocolErrors() const noexcept { return protocolErrors_; }

 protected:
  std::uint64_t protocolErrors_ = 0;
};

}  // namespace xr::sim
