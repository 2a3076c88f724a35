#pragma once
// CanBus on Linux SocketCAN: one raw AF_CAN socket bound to an interface
// (can0, vcan0), kernel filters, error frames, bus-off recovery by the
// kernel's restart-ms (ip link set can0 type can restart-ms 100): a bus-off
// error frame is counted and the socket keeps reading. Thin on purpose:
// everything above it runs on the simulated bus; this is tested only on the
// real-kernel rig (make test-kernel, vcan), since CI machines have no AF_CAN.
#include <string>
#include <vector>

#include "drivers/hal/can_bus.h"

namespace xr::can {

struct CanFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;
  bool extended = false;
};

class SocketCanBus final : public CanBus {
 public:
  // Opens and binds; throws std::runtime_error with the errno text when the
  // interface is missing or the kernel has no CAN support. Receives only
  // frames matching `filters` (all when empty) and every error class.
  SocketCanBus(const std::string& interface, const std::vector<CanFilter>& filters = {});
  ~SocketCanBus() override;
  SocketCanBus(const SocketCanBus&) = delete;
  SocketCanBus& operator=(const SocketCanBus&) = delete;

  bool send(const CanFrame& f) noexcept override;
  std::optional<CanFrame> receive(std::chrono::milliseconds timeout) noexcept override;
  CanBusStats stats() const noexcept override { return stats_; }

 private:
  int fd_ = -1;
  CanBusStats stats_;
};

}  // namespace xr::can
