#include "drivers/sim/sim_i2c_bus.h"

#include <cerrno>

namespace xr::sim {

void SimI2cBus::attach(std::uint16_t addr, SimI2cDevice* dev) noexcept {
  if (addr < devs_.size()) {
    devs_[addr] = dev;
    acking_[addr] = nack_[addr] ? nullptr : dev;
    updatedTo_[addr] = kNever;
  }
}
void SimI2cBus::detach(std::uint16_t addr) noexcept {
  if (addr < devs_.size()) {
    devs_[addr] = nullptr;
    acking_[addr] = nullptr;
    updatedTo_[addr] = kNever;
  }
}
void SimI2cBus::setNack(std::uint16_t addr, bool n) noexcept {
  if (addr < nack_.size()) {
    nack_[addr] = n;
    acking_[addr] = n ? nullptr : devs_[addr];
  }
}
bool SimI2cBus::nack(std::uint16_t addr) const noexcept { return addr < nack_.size() && nack_[addr]; }

int SimI2cBus::transfer(std::span<I2cMsg> msgs) noexcept {
  ++transfers_;
  if (msgs.empty()) {
    ++failed_;
    return EINVAL;
  }
  const TimeNs t = now_ ? *now_ : 0;
  for (auto& m : msgs) {
    // i2c-dev rejects 10-bit addresses unless I2C_TEN is set; we have none.
    SimI2cDevice* const d = m.addr < acking_.size() ? acking_[m.addr] : nullptr;
    if (d == nullptr) {  // absent chip or NACK fault
      ++failed_;
      return EREMOTEIO;
    }
    if (m.len > 0 && m.buf == nullptr) {
      ++failed_;
      return EFAULT;
    }
    if (updatedTo_[m.addr] != t) {  // once per chip and instant (update() is monotonic)
      d->update(t);
      updatedTo_[m.addr] = t;
    }
    const int rc = m.read ? d->read(m.buf, m.len) : d->write(m.buf, m.len);
    if (rc != 0) {
      ++failed_;
      return rc;
    }
  }
  return 0;
}

}  // namespace xr::sim
