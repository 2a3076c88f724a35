#pragma once
// Shared bits for running the drivers against the simulator's chip models:
// a virtual time the SimI2cBus reads and a Clock over it.
#include <cerrno>
#include <cstdint>
#include <vector>

#include "drivers/hal/clock.h"
#include "drivers/sim/sim_i2c_bus.h"

namespace xr::test {

struct VirtualTime {
  TimeNs now = 1'000'000'000;
};

class VirtualClock final : public Clock {
 public:
  explicit VirtualClock(VirtualTime& t) : t_(t) {}
  TimeNs now() const noexcept override { return t_.now; }
  void sleepUntil(TimeNs t) noexcept override {
    if (t > t_.now) t_.now = t;
  }
  // Simulated I2C/CPU latency: each now() call could advance time (tests of
  // late ADS edges set this).
 private:
  VirtualTime& t_;
};

// An I2cBus in front of another that records every message and can fail a
// future transfer at a chosen message: the messages before it reach the
// chips, as on a real adapter that stops at a NACK part-way through a
// combined transaction.
class RecordingBus final : public I2cBus {
 public:
  struct Msg {
    std::uint16_t addr;
    bool read;
    std::size_t len;
    std::uint8_t first;  // first byte of a write (the register pointer)
  };
  explicit RecordingBus(I2cBus& inner) : inner_(inner) {}

  int transfer(std::span<I2cMsg> msgs) noexcept override {
    sizes_.push_back(msgs.size());
    for (const auto& m : msgs)
      log_.push_back({m.addr, m.read, m.len, (!m.read && m.len > 0) ? m.buf[0] : std::uint8_t{0}});
    if (failAt_ >= 0 && static_cast<std::size_t>(failAt_) < msgs.size()) {
      const auto at = static_cast<std::size_t>(failAt_);
      failAt_ = -1;
      ++injected_;
      if (at > 0) {
        const int rc = inner_.transfer(msgs.first(at));
        if (rc != 0) return rc;
      }
      return EREMOTEIO;
    }
    return inner_.transfer(msgs);
  }
  // The next transfer with more than `messageIndex` messages fails there.
  void failNext(int messageIndex) { failAt_ = messageIndex; }
  int injected() const { return injected_; }
  void clear() {
    log_.clear();
    sizes_.clear();
  }
  const std::vector<Msg>& log() const { return log_; }
  const std::vector<std::size_t>& sizes() const { return sizes_; }  // messages per transfer

 private:
  I2cBus& inner_;
  std::vector<Msg> log_;
  std::vector<std::size_t> sizes_;
  int failAt_ = -1;
  int injected_ = 0;
};

}  // namespace xr::test
