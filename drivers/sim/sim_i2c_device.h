#pragma once
// A register-level chip model on the simulated I2C bus, in the shape of
// ArduPilot's SITL I2C devices: each message of a combined transaction is
// handed to the chip as a write or a read, and the chip converts on the
// simulated clock through update(). Return 0 or a positive errno; a chip
// that would not accept what it was sent answers EREMOTEIO (NACK), so a driver
// bug surfaces as an I/O error in tests instead of silently "working".
#include <cstddef>
#include <cstdint>

#include "core/time.h"

namespace xr::sim {

class SimI2cDevice {
 public:
  virtual ~SimI2cDevice() = default;
  // Bring the chip's conversions up to simulated time t (monotonic).
  virtual void update(TimeNs t) noexcept = 0;
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
