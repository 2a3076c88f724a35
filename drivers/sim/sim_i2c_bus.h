#pragma once
// Simulated I2C bus: the same I2cBus seam the Linux i2c-dev bus implements,
// dispatching each message by 7-bit address to a chip model. An absent chip,
// or one with a NACK fault injected, fails the transfer with EREMOTEIO like
// i2c-dev does when the address is not acknowledged.
#include <array>
#include <cstdint>

#include "drivers/hal/i2c_bus.h"
#include "drivers/sim/sim_i2c_device.h"

namespace xr::sim {

class SimI2cBus final : public I2cBus {
 public:
  // `now` is read before each transfer so chips convert up to that instant.
  explicit SimI2cBus(const TimeNs* now) : now_(now) { updatedTo_.fill(kNever); }

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
  static constexpr TimeNs kNever = INT64_MIN;
  const TimeNs* now_;
  std::array<SimI2cDevice*, 128> devs_{};
  std::array<bool, 128> nack_{};
  // devs_ with the NACKing addresses cleared: what transfer() looks up (one
  // load per message instead of three checks).
  std::array<SimI2cDevice*, 128> acking_{};
  // The instant each address's chip was last brought up to by transfer():
  // update() is monotonic (a no-op for a time it has reached), so the ~8
  // transfers of one control tick, all at the same simulated instant, call it
  // once per chip instead of once per transfer.
  std::array<TimeNs, 128> updatedTo_{};
  std::uint64_t transfers_ = 0;
  std::uint64_t failed_ = 0;
};

}  // namespace xr::sim
