#pragma once
// Simulated I2C bus: the same I2cBus seam the Linux i2c-dev bus implements,
// handing each run of messages to one 7-bit address to that chip model in
// one call (SimI2cDevice::transact). An absent chip, or one with a NACK fault
// injected, fails the transfer with EREMOTEIO like i2c-dev does when the
// address is not acknowledged; the messages before it took effect.
#include <array>
#include <cstdint>

#include "drivers/hal/i2c_bus.h"
#include "drivers/sim/sim_i2c_device.h"

namespace xr::sim {

class SimI2cBus final : public I2cBus {
 public:
  // `now` is read before each transfer so chips convert up to that instant.
  // A null `now` reads as time 0.
  explicit SimI2cBus(const TimeNs* now) : now_(now ? now : &kTimeZero) {}

  // The device is not owned. Attaching at an occupied address replaces it.
  void attach(std::uint16_t addr, SimI2cDevice* dev) noexcept;
  void detach(std::uint16_t addr) noexcept;
  // A NACK fault: the chip stops acknowledging its address (ina228_nack, ...).
  void setNack(std::uint16_t addr, bool nack) noexcept;
  bool nack(std::uint16_t addr) const noexcept;

  int transfer(std::span<I2cMsg> msgs) noexcept override;

  std::uint64_t transfers() const noexcept { return transfers_; }
  std::uint64_t failedTransfers() const noexcept { return failed_; }

 private:
  static constexpr TimeNs kTimeZero = 0;

  const TimeNs* now_;
  std::array<SimI2cDevice*, 128> devs_{};
  std::array<bool, 128> nack_{};
  std::uint64_t transfers_ = 0;
  std::uint64_t failed_ = 0;
};

}  // namespace xr::sim
