#include "drivers/sim/sim_i2c_bus.h"

#include <cerrno>

namespace xr::sim {

void SimI2cBus::attach(std::uint16_t addr, SimI2cDevice* dev) noexcept {
  if (addr < devs_.size()) devs_[addr] = dev;
}
void SimI2cBus::detach(std::uint16_t addr) noexcept {
  if (addr < devs_.size()) devs_[addr] = nullptr;
}
void SimI2cBus::setNack(std::uint16_t addr, bool n) noexcept {
  if (addr < nack_.size()) nack_[addr] = n;
}
bool SimI2cBus::nack(std::uint16_t addr) const noexcept { return addr < nack_.size() && nack_[addr]; }

int SimI2cBus::transfer(std::span<I2cMsg> msgs) noexcept {
  ++transfers_;
  if (msgs.empty()) {
    ++failed_;
    return EINVAL;
  }
  I2cMsg* m = msgs.data();
  I2cMsg* const end = m + msgs.size();
  const TimeNs t = *now_;
  do {
    // The run of messages to one address goes to the chip in one
    // transact(), which stops at a message without a buffer (EFAULT) or one
    // the chip refuses; the outcome is the one of dispatching the messages
    // singly. An absent or NACKing address fails with EREMOTEIO (i2c-dev
    // rejects 10-bit addresses unless I2C_TEN is set; we have none).
    const std::uint16_t addr = m->addr;
    SimI2cDevice* const d = addr < devs_.size() && !nack_[addr] ? devs_[addr] : nullptr;
    if (d == nullptr) {
      ++failed_;
      return EREMOTEIO;
    }
    I2cMsg* run = m + 1;
    while (run != end && run->addr == addr) ++run;
    const int rc = d->transact(t, std::span<I2cMsg>(m, std::size_t(run - m)));
    if (rc != 0) {
      ++failed_;
      return rc;
    }
    m = run;
  } while (m != end);
  return 0;
}
}  // namespace xr::sim
